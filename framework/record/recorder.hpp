#pragma once
// `brickyard run --record FILE`: every wire's samples (or those --record-only selects),
// serialized as on the wire (CDR), with the run's clock at publication and each type's IDL text,
// so a file explains itself. FILE.db3 is SQLite (after rosbag2's .db3); any other name is MCAP
// (chunked, zstd or lz4, indexed: what Foxglove and rosbag2 open). Both in docs/recording.md.
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace brickyard::mcap { class Writer; }

namespace brickyard::fw {

class Recorder {
 public:
  // Creates the file; throws std::runtime_error naming it (an existing file is not overwritten).
  // compression: MCAP's chunks', "zstd", "lz4" or "none" (ignored for .db3). profile: MCAP's,
  // "brickyard" (omgidl schemas, wires named node.port) or "ros2" (a ROS 2 bag's: ros2msg schemas,
  // topics /brickyard/node/port; mcap/ros2_profile.hpp); a .db3 is refused any but "brickyard".
  explicit Recorder(const std::string& path, const std::string& compression = "zstd", const std::string& profile = "brickyard");
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  void set_metadata(const std::string& key, const std::string& value);
  // A topic ("node.port") of a message type; returns its id for write().
  int add_topic(const std::string& name, const std::string& type);
  // A channel of messages that are no wire's (the scene's, in Foxglove's schemas: encoding "json",
  // schema_encoding "jsonschema"): its id for write(), or 0 in a .db3 (which holds wires only).
  int add_channel(const std::string& topic, const std::string& encoding, const std::string& schema_name, const std::string& schema_encoding,
                  const std::string& schema);
  // One sample, serialized as on the wire (SampleSerializer), at the run's clock. Thread-safe.
  void write(int topic, std::int64_t stamp_ns, const unsigned char* cdr, std::size_t size);
  // Commits and closes, then renames PATH.part to PATH: a file at PATH is a whole recording.
  void close();

  const std::string& path() const { return path_; }
  const std::string& part() const { return part_; }
  std::uint64_t messages() const { return messages_; }
  std::uint64_t bytes() const { return bytes_; }

 private:
  struct Topic;
  void create_schema();
  void write_metadata_once();  // MCAP: the run's metadata, before the first channel
  void flush_batch(std::int64_t stamp_ns);  // commits (SQLite) or writes the chunk (MCAP) once a second
  void exec(const char* sql);
  [[noreturn]] void fail(const std::string& what);
  void publish();
  std::string path_, part_;  // the recording's name, and the name it is written under until closed
  bool published_ = false;
  bool ros2_ = false;
  sqlite3* db_ = nullptr;
  std::unique_ptr<mcap::Writer> mcap_;
  std::vector<std::pair<std::string, std::string>> metadata_;  // MCAP: written with the first topic
  sqlite3_stmt* insert_ = nullptr;
  std::vector<std::unique_ptr<Topic>> topics_;
  std::mutex m_;
  std::uint64_t messages_ = 0, bytes_ = 0, in_transaction_ = 0;
  std::chrono::steady_clock::time_point batch_wall_;  // when the open batch began
  std::int64_t batch_stamp_ = 0;                      // its first sample's time on the run's clock
  bool failed_ = false;
};

// The IDL text of a message type (with what it includes): the SDK's, or a ROS 2 standard type's
// (cdr/ros2_std_types.hpp); null when neither.
const char* idl_text(const std::string& type);
// The same as one self-contained OMG IDL text, as an MCAP schema ("omgidl") carries it: no
// #include lines, each included definition once and before what uses it.
std::string omgidl_schema(const std::string& idl);

// Whether a recording at this path is SQLite (.db3) rather than MCAP.
bool is_sqlite_recording(const std::string& path);

// Whether "node.port" matches one of the patterns ('*' matches any run of characters).
bool topic_selected(const std::string& topic, const std::vector<std::string>& patterns);

}  // namespace brickyard::fw
