#pragma once
// Reading a recording (`brickyard run --record`, docs/recording.md), framework-free: its topics
// and one topic's samples in order, from an MCAP file or an SQLite one (told by their first
// bytes). Used by the replay plugins and the report.
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

struct sqlite3;
namespace brickyard::mcap { class Reader; }

namespace brickyard::replay {

struct RecordedTopic {
  std::int64_t id = 0;
  std::string name, type, type_hash, idl;
};

struct RecordedSample {
  std::int64_t stamp_ns = 0;        // the run's clock when it was published
  std::vector<unsigned char> data;  // CDR, as on the wire
};

// A problem with the file; what() names it.
class RecordingError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Recording {
 public:
  // Read-only; throws RecordingError, also for an MCAP file that is damaged (truncated, a chunk
  // that does not decompress): its what() names the file, the byte offset and why.
  explicit Recording(const std::string& path);
  ~Recording();
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;

  const std::string& path() const { return path_; }
  const std::vector<RecordedTopic>& topics() const { return topics_; }
  const RecordedTopic* topic(const std::string& name) const;
  std::string metadata(const std::string& key) const;  // empty when absent
  // Every sample of a topic, in the order it was published.
  std::vector<RecordedSample> samples(const RecordedTopic& t) const;

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::string path_;
  sqlite3* db_ = nullptr;
  std::unique_ptr<mcap::Reader> mcap_;
  std::vector<RecordedTopic> topics_;
};

}  // namespace brickyard::replay
