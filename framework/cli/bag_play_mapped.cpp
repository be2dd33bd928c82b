// `bag play BAG --map FILE`: a ROS 2 bag of a team's own (rosbag2 MCAP, ros2msg schemas) played
// onto Brickyard's wires (docs/ros2.md). Each mapped topic's samples are converted by its type:
//   sensor_msgs/msg/PointCloud2  -> brickyard::msgs::PointCloud (the map's sensor_id and mount)
//   sensor_msgs/msg/NavSatFix    -> brickyard::msgs::GnssFix (the map's datum, receiver_id)
//   sensor_msgs/msg/Imu          -> brickyard::msgs::Imu
//   nav_msgs/msg/Odometry        -> brickyard::msgs::LocalizationEstimate (a team's localization)
//   brickyard_msgs/msg/T         -> brickyard::msgs::T as it is (a recording in ROS 2's profile)
// The bag's other topics are listed and skipped, said. A sample that does not fit its type stops
// the play naming it (exit 2); one whose bytes end early is counted, the first named, and skipped.
#include "cli/bag_map.hpp"
#include "cli/bag_players.hpp"
#include "graph/diagnostics.hpp"

#include "cdr/ros2_to_msgs.hpp"
#include "mcap/mcap_reader.hpp"
#include "mcap/ros2_profile.hpp"

#include <brickyard/msgs/GnssFix.h>
#include <brickyard/msgs/Imu.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/registry.hpp>

#include <GeographicLib/LocalCartesian.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

namespace brickyard::fw {

namespace {

// Where in the map a topic's entry is: "FILE#/topics/~1ouster~1points".
std::string entry_of(const BagMap& map, const std::string& topic) {
  return map.file + "#" + (nlohmann::json::json_pointer("/topics") / topic).to_string();
}

// A bag's channel: its topic and type as its schema names them.
struct Channel {
  std::string topic, type, encoding;
};

std::vector<Channel> bag_channels(const std::string& file) {
  std::unique_ptr<mcap::Reader> r;
  try {
    r = std::make_unique<mcap::Reader>(file);
  } catch (const mcap::ReadError& e) {
    throw InvalidInput(file, e.what());
  }
  if (const mcap::Damage* d = r->damage()) throw InvalidInput(file, "damaged at byte " + std::to_string(d->offset) + ": " + d->what);
  std::vector<Channel> out;
  for (const auto& [id, c] : r->channels()) {
    const auto sc = r->schemas().find(c.schema);
    out.push_back({c.topic, sc == r->schemas().end() ? "" : sc->second.name, sc == r->schemas().end() ? "" : sc->second.encoding});
  }
  return out;
}

std::function<void(const unsigned char*, std::size_t)> cloud_player(DdsWriter* w, const MappedTopic& t) {
  auto msg = std::make_shared<msgs::PointCloud>();
  auto cols = std::make_shared<cdr::CloudColumns>();
  const cdr::CloudMount mount{t.sensor_id, t.mount};
  return [w, mount, msg, cols, seq = std::uint32_t{0}](const unsigned char* data, std::size_t size) mutable {
    cdr::read_pointcloud2(data, size, *cols);
    cdr::to_point_cloud(*cols, mount, seq++, *msg);
    w->write(msg.get());
  };
}

std::function<void(const unsigned char*, std::size_t)> fix_player(DdsWriter* w, const MappedTopic& t, const std::array<double, 3>& datum) {
  auto local = std::make_shared<GeographicLib::LocalCartesian>(datum[0], datum[1], datum[2]);
  return [w, receiver = t.receiver_id, local, seq = std::uint32_t{0}](const unsigned char* data, std::size_t size) mutable {
    const cdr::NavSatFixValues v = cdr::read_navsatfix(data, size);
    std::array<double, 3> enu{};
    local->Forward(v.latitude, v.longitude, v.altitude, enu[0], enu[1], enu[2]);
    msgs::GnssFix f;
    cdr::to_gnss_fix(v, enu, receiver, seq++, f);
    w->write(&f);
  };
}

std::function<void(const unsigned char*, std::size_t)> imu_player(DdsWriter* w) {
  return [w, seq = std::uint32_t{0}](const unsigned char* data, std::size_t size) mutable {
    msgs::Imu m;
    cdr::to_imu(cdr::read_imu(data, size), seq++, m);
    w->write(&m);
  };
}

std::function<void(const unsigned char*, std::size_t)> odometry_player(DdsWriter* w) {
  return [w, seq = std::uint32_t{0}](const unsigned char* data, std::size_t size) mutable {
    msgs::LocalizationEstimate e;
    cdr::to_estimate(cdr::read_odometry(data, size), seq++, e);
    w->write(&e);
  };
}

// Our own message (a recording in ROS 2's profile): deserialized as it is.
std::function<void(const unsigned char*, std::size_t)> own_player(Played& p, const std::string& type) {
  const auto* entry = msgs::find_type(type.c_str());
  p.support.reset(entry->make());
  p.sample = p.support->createData();
  return [&p](const unsigned char* data, std::size_t size) {
    if (p.payload.max_size < size) p.payload.reserve(static_cast<std::uint32_t>(size));
    std::memcpy(p.payload.data, data, size);
    p.payload.length = static_cast<std::uint32_t>(size);
    p.payload.pos = 0;
    if (!p.support->deserialize(&p.payload, p.sample)) throw cdr::DamagedSample(std::string("does not decode as ") + p.support->getName());
    p.writer->write(p.sample);
  };
}

// The wire's type for a bag's type, or empty when none is converted.
std::string wire_type_of(const Channel& c) {
  if (c.type == "sensor_msgs/msg/PointCloud2") return "brickyard::msgs::PointCloud";
  if (c.type == "sensor_msgs/msg/NavSatFix") return "brickyard::msgs::GnssFix";
  if (c.type == "sensor_msgs/msg/Imu") return "brickyard::msgs::Imu";
  if (c.type == "nav_msgs/msg/Odometry") return "brickyard::msgs::LocalizationEstimate";
  const std::string ours = mcap::brickyard_names(c.topic, c.type, c.encoding).second;
  return ours != c.type && msgs::find_type(ours.c_str()) ? ours : std::string();
}

void add_player(const BagMap& map, const MappedTopic& t, const Channel& c, DdsTransport& dds, Players& topics) {
  const std::string type = wire_type_of(c);
  if (type.empty())
    throw InvalidInput(entry_of(map, t.topic), "the bag's " + t.topic + " holds " + (c.type.empty() ? "no schema" : c.type) +
                                                            ", which bag play does not convert (it converts sensor_msgs/msg/PointCloud2, "
                                                            "NavSatFix, Imu, nav_msgs/msg/Odometry and brickyard_msgs)");
  if (type == "brickyard::msgs::GnssFix" && !map.datum)
    throw InvalidInput(map.file + "#/datum", "missing: " + t.topic + " is a NavSatFix, placed on the map from this origin");
  const auto dot = t.wire.find('.');
  auto p = std::make_unique<Played>();
  p->writer = dds.make_writer(topic_name(t.wire.substr(0, dot), t.wire.substr(dot + 1)), type);
  if (type == "brickyard::msgs::PointCloud") p->convert = cloud_player(p->writer, t);
  else if (type == "brickyard::msgs::GnssFix") p->convert = fix_player(p->writer, t, *map.datum);
  else if (type == "brickyard::msgs::Imu" && c.type == "sensor_msgs/msg/Imu") p->convert = imu_player(p->writer);
  else if (c.type == "nav_msgs/msg/Odometry") p->convert = odometry_player(p->writer);
  else p->convert = own_player(*p, type);
  // Keyed as the recording's reader names the channel (record/recording_info.hpp).
  topics[mcap::brickyard_names(c.topic, c.type, c.encoding).first] = std::move(p);
}

}  // namespace

int make_mapped_players(const BagPlayOptions& o, DdsTransport& dds, Players& topics) {
  try {
    const BagMap map = read_bag_map(o.map);
    const std::vector<Channel> channels = bag_channels(o.file);
    std::string skipped, names;
    for (const Channel& c : channels) names += (names.empty() ? "" : ", ") + c.topic;
    for (const MappedTopic& t : map.topics) {
      const auto c = std::find_if(channels.begin(), channels.end(), [&](const Channel& ch) { return ch.topic == t.topic; });
      if (c == channels.end())
        throw InvalidInput(entry_of(map, t.topic), "the bag " + o.file + " has no topic " + t.topic + " (its topics: " + names + ")");
      add_player(map, t, *c, dds, topics);
    }
    for (const Channel& c : channels)
      if (std::none_of(map.topics.begin(), map.topics.end(), [&](const MappedTopic& t) { return t.topic == c.topic; }))
        skipped += (skipped.empty() ? "" : ", ") + c.topic + " (" + c.type + ")";
    if (!skipped.empty()) std::fprintf(stderr, "bag play: not in the map, not played: %s\n", skipped.c_str());
  } catch (const InvalidInput& e) {
    for (const auto& d : e.diagnostics()) std::fprintf(stderr, "error: %s: %s\n", d.where.c_str(), d.message.c_str());
    return 2;
  }
  return 0;
}

}  // namespace brickyard::fw
