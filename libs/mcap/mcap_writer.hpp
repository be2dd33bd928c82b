#pragma once
// Writes an MCAP file (https://mcap.dev/spec): chunked, each chunk compressed (zstd or lz4) with
// its message index, schemas and channels before the chunks that use them, and at close a
// summary (schemas, channels, statistics, chunk and metadata indexes) and the footer. What a
// crash leaves is the chunks written so far: a reader reads them up to the damage. Framework-
// free; the recorder (`brickyard run --record FILE.mcap`) feeds it.
#include "mcap_format.hpp"

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::mcap {

enum class Compression { None, Zstd, Lz4 };
// "zstd", "lz4", "none"; false for anything else.
bool parse_compression(std::string_view name, Compression& out);

struct WriterOptions {
  Compression compression = Compression::Zstd;
  int zstd_level = 3;                       // zstd's default: about 3.5× on the main job's samples, fast
  std::uint64_t chunk_size = 4u << 20;      // uncompressed bytes: a chunk is closed once it holds this many
  std::string profile, library = "brickyard";
};

class Writer {
 public:
  // Creates the file exclusively (an existing file is never replaced); throws std::runtime_error
  // naming it.
  Writer(const std::string& path, WriterOptions opt = {});
  ~Writer();  // closes (errors swallowed: call close() to see them)
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  std::uint16_t add_schema(const std::string& name, const std::string& encoding, std::string_view data);
  std::uint16_t add_channel(std::uint16_t schema, const std::string& topic, const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  // A Metadata record, written at once (outside any chunk).
  void add_metadata(const std::string& name, const std::map<std::string, std::string>& values);
  void write(std::uint16_t channel, std::uint64_t log_time, std::uint64_t publish_time, const void* data, std::size_t size);
  // Writes the open chunk now (the recorder does every second: what a crash can lose).
  void flush();
  // The summary and footer; the file is complete (and indexed) only after this. Throws on a write error.
  void close();

  const std::string& path() const { return path_; }
  std::uint64_t messages() const { return messages_; }
  std::uint64_t chunk_bytes() const { return chunk_.size(); }  // uncompressed bytes in the open chunk

 private:
  void record(Op op, const std::string& content);  // to the file
  void put(const void* p, std::size_t n);
  [[noreturn]] void fail(const std::string& what);
  // The summary's groups of records, written by close() in this order.
  void write_summary_schemas();
  void write_summary_channels();
  void write_statistics();
  void write_chunk_indexes();
  void write_metadata_indexes();
  struct Schema {
    std::string name, encoding, data;
  };
  struct Channel {
    std::uint16_t schema;
    std::string topic, encoding;
    std::map<std::string, std::string> metadata;
  };
  struct ChunkIndex {
    std::uint64_t start, end, offset, length, index_length, compressed, uncompressed;
    std::map<std::uint16_t, std::uint64_t> index_offsets;
  };
  struct MetadataIndex {
    std::uint64_t offset, length;
    std::string name;
  };
  std::string path_;
  WriterOptions opt_;
  std::FILE* f_ = nullptr;
  std::uint64_t offset_ = 0;  // bytes written so far
  bool failed_ = false;
  std::vector<Schema> schemas_;
  std::vector<Channel> channels_;
  std::vector<ChunkIndex> chunk_indexes_;
  std::vector<MetadataIndex> metadata_indexes_;
  // The open chunk: its records, per channel its messages' (log_time, offset in the chunk).
  std::string chunk_;
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::uint64_t chunk_start_ = 0, chunk_end_ = 0;
  std::string compressed_, content_;  // reused buffers
  std::uint64_t messages_ = 0, first_ = 0, last_ = 0;
  std::vector<std::uint64_t> channel_counts_;
  std::vector<std::uint32_t> sequence_;
};

}  // namespace brickyard::mcap
