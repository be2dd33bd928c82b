#pragma once
// bag play's players (cli/bag_play.cpp): each played topic's writer and what turns a recorded
// sample into the message it writes, and the loop that plays them at their recorded times. A
// Brickyard recording's topics are deserialized as they are; a ROS 2 bag's, through --map, are
// converted (cli/bag_play_mapped.cpp).
#include "cli/bag_play.hpp"
#include "transport/dds.hpp"

#include <brickyard/msgs/PointCloud.h>

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>

namespace brickyard::fw {

// One played topic's writer and a message object to deserialize its samples into.
struct Played {
  DdsWriter* writer = nullptr;
  std::unique_ptr<eprosima::fastdds::dds::TopicDataType> support;
  void* sample = nullptr;
  eprosima::fastrtps::rtps::SerializedPayload_t payload;
  std::uint64_t count = 0;
  bool packed = false;     // a QuantizedPointCloud, played as the PointCloud it was (--record-cloud-precision)
  msgs::PointCloud cloud;
  // A ROS 2 bag's sample converted and written; throws std::invalid_argument when it does not fit
  // its type, cdr::DamagedSample when its bytes end early (counted, the first named, skipped). Set,
  // it replaces the deserialization.
  std::function<void(const unsigned char*, std::size_t)> convert;
  std::uint64_t damaged = 0;
  std::string first_damage;
  ~Played() {
    if (sample) support->deleteData(sample);
  }
};
// By the topic's name as the recording's reader gives it (record/recording_info.hpp).
using Players = std::map<std::string, std::unique_ptr<Played>>;
using Clock = std::chrono::steady_clock;

// Every sample of the played topics at its recorded time from `start` (`rate` times as fast),
// until the end or Ctrl-C: empty, or what went wrong. `played` counts them.
std::string play_samples(const BagPlayOptions& o, Players& topics, Clock::time_point start, std::uint64_t& played);

// --map: the players of a ROS 2 bag's mapped topics (cli/bag_map.hpp): 0, or 2 said on stderr (the
// map or the bag unreadable, a mapped topic the bag lacks or of a type not converted).
int make_mapped_players(const BagPlayOptions& o, DdsTransport& dds, Players& topics);

}  // namespace brickyard::fw
