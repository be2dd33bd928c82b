#pragma once
// What a recording (`brickyard run --record FILE`, docs/recording.md) holds, read without its
// samples: its clock, how many samples and until when, its topics. For commands that run a graph
// on a recording (`brickyard map build`) and must say what is wrong with the file first.
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::fw {

struct RecordingInfo {
  std::string clock;                                       // "sim" or "real" (metadata)
  std::uint64_t messages = 0;                              // the last sample's id: how many were written
  std::int64_t last_ns = 0;                                // the last sample's time, the run's clock
  std::vector<std::pair<std::string, std::string>> topics;  // name, type
  std::string damage;  // MCAP: where the reading stopped short and why ("byte N: ..."); empty: whole
};

// An MCAP file (told by its first bytes) or an SQLite one. Throws std::runtime_error saying what
// is wrong: not there, neither, not a recording (the tables are not ours), unreadable. A damaged
// MCAP file (truncated, a bad chunk) is read up to the damage, which `damage` then names.
RecordingInfo read_recording_info(const std::string& path);

// Per topic: its samples (reads every sample's row, not its data: seconds for gigabytes).
struct TopicStats {
  std::string name, type;
  std::uint64_t count = 0, bytes = 0;
  std::int64_t first_ns = 0, last_ns = 0;
};
// In the recording's topic order; topics without samples included (count 0). Throws as above.
std::vector<TopicStats> read_topic_stats(const std::string& path);
// Every sample, in the order it was published: its topic, type, the run's clock and its CDR
// bytes (`brickyard bag play`). Throws as above; a damaged MCAP file after the samples before the
// damage were given.
void for_each_sample(const std::string& path, const std::function<void(const std::string& topic, const std::string& type, std::int64_t stamp_ns,
                                                                     const unsigned char* data, std::size_t size)>& f);
// Both from one reading of an MCAP file (its chunks are decompressed once).
void read_mcap_recording(const std::string& path, RecordingInfo& info, std::vector<TopicStats>& topics);
// Whether the file is MCAP (else SQLite is tried); std::runtime_error when it is not a regular
// file that can be opened (a FIFO, a device, a folder: exit 2 from the commands), before a byte is read.
bool is_mcap_file(const std::string& path);

}  // namespace brickyard::fw
