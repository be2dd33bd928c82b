#pragma once
// `brickyard run --record FILE`: every wire's samples (or those --record-only selects) in an
// SQLite file, serialized as on the wire (CDR), with the run's clock at publication and each
// type's IDL text, so a file explains itself. Schema in docs/recording.md (after rosbag2's .db3).
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

struct sqlite3;
struct sqlite3_stmt;

namespace eprosima::fastdds::dds { class TopicDataType; }

namespace brickyard::fw {

class Recorder {
 public:
  // Creates the file; throws std::runtime_error naming it (an existing file is not overwritten).
  explicit Recorder(const std::string& path);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  void set_metadata(const std::string& key, const std::string& value);
  // A topic ("node.port") of a message type; returns its id for write().
  int add_topic(const std::string& name, const std::string& type);
  // One sample (the message object of the topic's type) at the run's clock. Thread-safe.
  void write(int topic, std::int64_t stamp_ns, const void* message);
  // Commits and closes; the file is complete only after this.
  void close();

  const std::string& path() const { return path_; }
  std::uint64_t messages() const { return messages_; }
  std::uint64_t bytes() const { return bytes_; }

 private:
  struct Topic;
  void create_schema();
  void exec(const char* sql);
  [[noreturn]] void fail(const std::string& what);
  std::string path_;
  sqlite3* db_ = nullptr;
  sqlite3_stmt* insert_ = nullptr;
  std::vector<std::unique_ptr<Topic>> topics_;
  std::mutex m_;
  std::uint64_t messages_ = 0, bytes_ = 0, in_transaction_ = 0;
  std::chrono::steady_clock::time_point batch_wall_;  // when the open batch began
  std::int64_t batch_stamp_ = 0;                      // its first sample's time on the run's clock
  bool failed_ = false;
};

// The IDL text of a message type (with what it includes), or null.
const char* idl_text(const std::string& type);

// Whether "node.port" matches one of the patterns ('*' matches any run of characters).
bool topic_selected(const std::string& topic, const std::vector<std::string>& patterns);

}  // namespace brickyard::fw
