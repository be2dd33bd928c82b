#pragma once
// Fast DDS behind a small interface: one participant per process, a writer per output port,
// a reader per input whose writer lives in another process.
#include "graph/graph.hpp"

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace eprosima::fastdds::dds {
class DomainParticipant;
class Publisher;
class Subscriber;
class DataWriter;
class DataReader;
class Topic;
}

namespace brickyard::fw {

// Topic of an output port: every wire is a DDS topic any DDS application can subscribe to.
std::string topic_name(const std::string& node, const std::string& port);

// The names a topic and a type have on the wire. Brickyard's own: as they are. ROS 2's (a graph's
// transport.naming "ros2", docs/ros2.md): the topic as ROS 2's DDS middlewares write the ROS
// topic "/brickyard/node/port" ("rt/brickyard/node/port"), the type as they name a message type
// of the package `brickyard ros2 msgs` writes ("brickyard::msgs::Imu" ->
// "brickyard_msgs::msg::dds_::Imu_"), the CDR unchanged.
std::string wire_topic(const std::string& topic, bool ros2);
std::string wire_type(const std::string& type, bool ros2);

class DdsWriter {
 public:
  // Same-process readers take the pointer path; serialization is skipped while no reader in
  // another participant is matched.
  bool has_remote_readers() const { return matched_.load(std::memory_order_relaxed) > 0; }
  int matched() const { return matched_.load(); }
  bool write(const void* sample);
  // Until every matched reader has acknowledged what was written, at most `seconds`: whether they did.
  bool wait_acked(double seconds);

 private:
  friend class DdsTransport;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
  std::atomic<int> matched_{0};
  std::unique_ptr<struct WriterListener> listener_;
};

class DdsReader {
 public:
  // Writers in other participants matched with this reader now (a split run's start-up waits for them).
  int matched() const { return matched_.load(); }
  // Distinct writers whose samples this reader delivered over the run: 1 on a healthy wire (more
  // after a restart, or when a second writer under the expected name fed it).
  int writers_heard() const;

 private:
  friend class DdsTransport;
  std::atomic<int> matched_{0};
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
  std::unique_ptr<struct ReaderListener> listener_;
};

// DDS security (OMG DDS Security 1.1 through Fast DDS's builtin plugins: PKI-DH authentication,
// access control by signed permissions, AES-GCM-GMAC): the participant's files, absolute paths.
// Empty identity_ca: security off.
struct DdsSecurity {
  std::string identity_ca, permissions_ca, governance;  // shared by every participant of the graph
  std::string cert, key, permissions;                   // this participant's identity
  bool on() const { return !identity_ca.empty(); }
};

struct DdsSettings {
  int domain = 0;
  std::vector<std::string> interfaces{"127.0.0.1"};
  std::vector<std::string> peers{"127.0.0.1"};
  std::uint32_t shm_segment_bytes = 16u << 20;  // 2 MiB samples between processes need >= 4 MiB
  bool shared_memory = true;  // off: UDP on the allowed interfaces only (transport.shared_memory)
  // The participant's name, which its peers see: a graph's process is "brickyard:PROCESS", so a
  // reader can tell its graph's writers from any other (participant_name()).
  // Called on a DDS thread for each writer another participant announces (`brickyard topic`):
  // its DDS topic and type names.
  std::function<void(const std::string& topic, const std::string& type)> on_writer;
  std::string name = "brickyard";
  DdsSecurity security;
  bool ros2_naming = false;  // topics and types named as ROS 2 names them (wire_topic, wire_type)
  // A split run on the sim clock (exec/lockstep.hpp): no sample may be lost between processes, so
  // writers and readers keep all (no depth drops the oldest unacknowledged one) and a writer
  // blocks, at most 10 s, rather than overwrite.
  bool lockstep = false;
};

// What a graph's process calls its DDS participant.
inline std::string participant_name(const std::string& process) { return "brickyard:" + process; }

// The topic a process of a split sim-clock run publishes its clock records on (exec/lockstep.hpp).
inline std::string clock_topic(const std::string& process) { return "brickyard_clock/" + process; }

// The topic a process of a split run on the real clock says how its run ended on (exec/peer_ends.hpp).
inline std::string end_topic(const std::string& process) { return "brickyard_end/" + process; }

// A reader's check of who writes to it: samples from a writer whose participant is not named
// `expected` are dropped unless `accept_others`, and `other` is told once per such writer
// (its participant's name, its GUID).
struct WriterCheck {
  std::string expected;
  bool accept_others = false;
  std::function<void(const std::string& participant, const std::string& writer)> other;
};

class DdsTransport {
 public:
  explicit DdsTransport(const DdsSettings& s);  // throws std::runtime_error
  ~DdsTransport();
  DdsTransport(const DdsTransport&) = delete;
  DdsTransport& operator=(const DdsTransport&) = delete;

  DdsWriter* make_writer(const std::string& topic, const std::string& type_name);
  // `deliver` runs on a DDS thread with each received sample; `liveliness` (when set) with false
  // when a writer's liveliness lapses (its process died or stopped for more than 0.5 s, not a
  // clean exit) and with true when a writer becomes alive (matched first, or back after a lapse).
  DdsReader* make_reader(const std::string& topic, const std::string& type_name, std::uint32_t depth,
                         std::function<void(std::shared_ptr<const void>)> deliver, std::function<void(bool)> liveliness = {},
                         WriterCheck check = {});
  // Stop deliveries before the objects they feed go away.
  void close_readers();

 private:
  eprosima::fastdds::dds::Topic* topic(const std::string& name, const std::string& type_name);
  bool secured_ = false;
  bool lockstep_ = false;
  bool ros2_naming_ = false;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  std::unique_ptr<struct DiscoveryListener> discovery_;
  std::shared_ptr<struct PeerNames> peers_;  // participants discovered: GUID prefix -> name
  eprosima::fastdds::dds::Publisher* publisher_ = nullptr;
  eprosima::fastdds::dds::Subscriber* subscriber_ = nullptr;
  std::vector<std::unique_ptr<DdsWriter>> writers_;
  std::vector<std::unique_ptr<DdsReader>> readers_;
};

}  // namespace brickyard::fw
