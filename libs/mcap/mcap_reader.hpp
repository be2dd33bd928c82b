#pragma once
// Reads an MCAP file (https://mcap.dev/spec) front to back, framework-free: its schemas, channels,
// metadata and messages, chunks decompressed (zstd, lz4) and checked against their CRC. Damage —
// a record running past the end, a chunk that does not decompress or whose CRC differs, a file
// that ends without its footer (a run that was killed) — stops the reading there: what came
// before is kept, and damage() says where and why. Nothing in the file is trusted: every length
// is checked against what is left, a chunk's size against a ceiling.
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::mcap {

// The file cannot be read at all (not there, not MCAP); what() names it.
class ReadError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SchemaInfo {
  std::uint16_t id = 0;
  std::string name, encoding, data;
};
struct ChannelInfo {
  std::uint16_t id = 0, schema = 0;
  std::string topic, encoding;
  std::map<std::string, std::string> metadata;
  std::uint64_t messages = 0;            // counted by the reading
  std::uint64_t bytes = 0;               // the messages' data
  std::uint64_t first = 0, last = 0;     // log times
};
struct MessageView {
  std::uint16_t channel = 0;
  std::uint32_t sequence = 0;
  std::uint64_t log_time = 0, publish_time = 0;
  const unsigned char* data = nullptr;
  std::size_t size = 0;
};
struct Damage {
  std::uint64_t offset = 0;  // bytes into the file
  std::string what;
};

class Reader {
 public:
  // Maps the file and reads it through once (schemas, channels, metadata, each channel's count).
  // Throws ReadError when it is not there or does not begin as MCAP.
  explicit Reader(const std::string& path);
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  const std::string& path() const { return path_; }
  const std::map<std::uint16_t, SchemaInfo>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, ChannelInfo>& channels() const { return channels_; }
  // Metadata records by name (several records of one name merged, the later winning).
  const std::map<std::string, std::map<std::string, std::string>>& metadata() const { return metadata_; }
  const ChannelInfo* channel(const std::string& topic) const;
  // Where the reading stopped short, or null: the file is whole.
  const Damage* damage() const { return damage_.what.empty() ? nullptr : &damage_; }

  // Every message (of the channels in `only`, when given) in the file's order, up to any damage.
  // A chunk none of whose messages is wanted is skipped without decompressing.
  void read(const std::function<void(const MessageView&)>& on_message, const std::set<std::uint16_t>* only = nullptr) const;

 private:
  struct Scan;
  void scan(Scan& s, const std::function<void(const MessageView&)>* on_message, const std::set<std::uint16_t>* only) const;
  std::string path_;
  const unsigned char* data_ = nullptr;
  std::size_t size_ = 0;
  std::map<std::uint16_t, SchemaInfo> schemas_;
  std::map<std::uint16_t, ChannelInfo> channels_;
  std::map<std::string, std::map<std::string, std::string>> metadata_;
  Damage damage_;
};

}  // namespace brickyard::mcap
