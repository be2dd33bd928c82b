#include "mcap_writer.hpp"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace brickyard::mcap {

bool parse_compression(std::string_view name, Compression& out) {
  if (name == "zstd") return out = Compression::Zstd, true;
  if (name == "lz4") return out = Compression::Lz4, true;
  if (name == "none") return out = Compression::None, true;
  return false;
}

namespace {
const char* compression_name(Compression c) { return c == Compression::Zstd ? "zstd" : c == Compression::Lz4 ? "lz4" : ""; }
std::uint32_t crc32_of(const std::string& s) {
  return static_cast<std::uint32_t>(::crc32(0L, reinterpret_cast<const Bytef*>(s.data()), static_cast<uInt>(s.size())));
}
void pack_map(Packer& pk, const std::map<std::string, std::string>& m) {
  std::string body;
  Packer b{body};
  for (const auto& [k, v] : m) b.str(k), b.str(v);
  pk.num(static_cast<std::uint32_t>(body.size()));
  pk.out += body;
}
}  // namespace

Writer::Writer(const std::string& path, WriterOptions opt) : path_(path), opt_(std::move(opt)) {
  // Created exclusively: two runs given the same FILE cannot both pass an exists() check.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    if (errno == EEXIST) throw std::runtime_error(path + ": exists; a recording is never overwritten");
    throw std::runtime_error(path + ": cannot create (" + std::strerror(errno) + ")");
  }
  f_ = ::fdopen(fd, "wb");
  if (!f_) {
    ::close(fd);
    throw std::runtime_error(path + ": cannot open for writing");
  }
  put(kMagic, sizeof kMagic);
  std::string c;
  Packer pk{c};
  pk.str(opt_.profile);
  pk.str(opt_.library);
  record(Op::Header, c);
}

Writer::~Writer() {
  try {
    close();
  } catch (...) {
  }
}

void Writer::fail(const std::string& what) {
  failed_ = true;
  throw std::runtime_error(path_ + ": " + what);
}

void Writer::put(const void* p, std::size_t n) {
  if (std::fwrite(p, 1, n, f_) != n) fail(std::string("writing (") + std::strerror(errno) + ")");
  offset_ += n;
}

void Writer::record(Op op, const std::string& content) {
  const auto code = static_cast<std::uint8_t>(op);
  const auto len = static_cast<std::uint64_t>(content.size());
  put(&code, 1);
  put(&len, 8);
  put(content.data(), content.size());
}

std::uint16_t Writer::add_schema(const std::string& name, const std::string& encoding, std::string_view data) {
  if (schemas_.size() >= 0xfffe) fail("more than 65534 schemas");
  const auto id = static_cast<std::uint16_t>(schemas_.size() + 1);  // 0: no schema
  schemas_.push_back({name, encoding, std::string(data)});
  std::string c;
  Packer pk{c};
  pk.num(id);
  pk.str(name);
  pk.str(encoding);
  pk.str(data);
  record(Op::Schema, c);
  return id;
}

std::uint16_t Writer::add_channel(std::uint16_t schema, const std::string& topic, const std::string& message_encoding,
                                  const std::map<std::string, std::string>& metadata) {
  if (channels_.size() >= 0xffff) fail("more than 65535 channels");
  const auto id = static_cast<std::uint16_t>(channels_.size());
  channels_.push_back({schema, topic, message_encoding, metadata});
  channel_counts_.push_back(0);
  sequence_.push_back(0);
  std::string c;
  Packer pk{c};
  pk.num(id);
  pk.num(schema);
  pk.str(topic);
  pk.str(message_encoding);
  pack_map(pk, metadata);
  record(Op::Channel, c);
  return id;
}

void Writer::add_metadata(const std::string& name, const std::map<std::string, std::string>& values) {
  if (failed_ || !f_) return;
  std::string c;
  Packer pk{c};
  pk.str(name);
  pack_map(pk, values);
  metadata_indexes_.push_back({offset_, 9 + c.size(), name});
  record(Op::Metadata, c);
}

void Writer::write(std::uint16_t channel, std::uint64_t log_time, std::uint64_t publish_time, const void* data, std::size_t size) {
  if (failed_ || !f_) return;
  if (channel >= channels_.size()) fail("a message on channel " + std::to_string(channel) + ", which was never added");
  if (chunk_.empty()) chunk_start_ = chunk_end_ = log_time;
  chunk_start_ = std::min(chunk_start_, log_time);
  chunk_end_ = std::max(chunk_end_, log_time);
  chunk_index_[channel].emplace_back(log_time, chunk_.size());
  // The Message record, straight into the chunk: opcode, length, channel, sequence, two times, data.
  Packer pk{chunk_};
  pk.num(static_cast<std::uint8_t>(Op::Message));
  pk.num(static_cast<std::uint64_t>(2 + 4 + 8 + 8 + size));
  pk.num(channel);
  pk.num(sequence_[channel]++);
  pk.num(log_time);
  pk.num(publish_time);
  chunk_.append(static_cast<const char*>(data), size);
  if (messages_ == 0) first_ = last_ = log_time;
  first_ = std::min(first_, log_time);
  last_ = std::max(last_, log_time);
  ++messages_;
  ++channel_counts_[channel];
  if (chunk_.size() >= opt_.chunk_size) flush();
}

void Writer::flush() {
  if (failed_ || !f_ || chunk_.empty()) return;
  const std::string* records = &chunk_;
  if (opt_.compression == Compression::Zstd) {
    compressed_.resize(ZSTD_compressBound(chunk_.size()));
    const std::size_t n = ZSTD_compress(compressed_.data(), compressed_.size(), chunk_.data(), chunk_.size(), opt_.zstd_level);
    if (ZSTD_isError(n)) fail(std::string("zstd: ") + ZSTD_getErrorName(n));
    compressed_.resize(n);
    records = &compressed_;
  } else if (opt_.compression == Compression::Lz4) {
    LZ4F_preferences_t prefs{};
    prefs.frameInfo.contentSize = chunk_.size();
    compressed_.resize(LZ4F_compressFrameBound(chunk_.size(), &prefs));
    const std::size_t n = LZ4F_compressFrame(compressed_.data(), compressed_.size(), chunk_.data(), chunk_.size(), &prefs);
    if (LZ4F_isError(n)) fail(std::string("lz4: ") + LZ4F_getErrorName(n));
    compressed_.resize(n);
    records = &compressed_;
  }
  content_.clear();
  Packer pk{content_};
  pk.num(chunk_start_);
  pk.num(chunk_end_);
  pk.num(static_cast<std::uint64_t>(chunk_.size()));
  pk.num(crc32_of(chunk_));
  pk.str(compression_name(opt_.compression));
  pk.num(static_cast<std::uint64_t>(records->size()));
  ChunkIndex ci{chunk_start_, chunk_end_, offset_, 0, 0, records->size(), chunk_.size(), {}};
  // The content's head, then the records without copying them again.
  const auto code = static_cast<std::uint8_t>(Op::Chunk);
  const std::uint64_t len = content_.size() + records->size();
  put(&code, 1);
  put(&len, 8);
  put(content_.data(), content_.size());
  put(records->data(), records->size());
  ci.length = offset_ - ci.offset;
  // One Message Index per channel, its entries in time order (samples of one topic published
  // from several threads can arrive a little out of it).
  const std::uint64_t index_start = offset_;
  for (auto& [channel, entries] : chunk_index_) {
    std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    content_.clear();
    Packer ip{content_};
    ip.num(channel);
    ip.num(static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [t, at] : entries) ip.num(t), ip.num(at);
    ci.index_offsets[channel] = offset_;
    record(Op::MessageIndex, content_);
  }
  ci.index_length = offset_ - index_start;
  chunk_indexes_.push_back(std::move(ci));
  chunk_.clear();
  chunk_index_.clear();
  if (std::fflush(f_) != 0) fail(std::string("writing (") + std::strerror(errno) + ")");
}

void Writer::close() {
  if (!f_) return;
  if (failed_) {  // the run is stopping; what was written stays as it is (a reader reads up to it)
    std::fclose(f_);
    f_ = nullptr;
    return;
  }
  flush();
  record(Op::DataEnd, std::string(4, '\0'));  // no CRC of the data section (the chunks carry theirs)
  // The summary: each group of records, and where each group starts (the Summary Offset section).
  const std::uint64_t summary_start = offset_;
  struct Group {
    Op op;
    std::uint64_t start, length;
  };
  std::vector<Group> groups;
  auto group = [&](Op op, void (Writer::*each)()) {
    const std::uint64_t start = offset_;
    (this->*each)();
    if (offset_ > start) groups.push_back({op, start, offset_ - start});
  };
  group(Op::Schema, &Writer::write_summary_schemas);
  group(Op::Channel, &Writer::write_summary_channels);
  group(Op::Statistics, &Writer::write_statistics);
  group(Op::ChunkIndex, &Writer::write_chunk_indexes);
  group(Op::MetadataIndex, &Writer::write_metadata_indexes);
  const std::uint64_t summary_offset_start = offset_;
  std::string c;
  for (const auto& g : groups) {
    c.clear();
    Packer pk{c};
    pk.num(static_cast<std::uint8_t>(g.op));
    pk.num(g.start);
    pk.num(g.length);
    record(Op::SummaryOffset, c);
  }
  c.clear();
  Packer pk{c};
  pk.num(summary_start);
  pk.num(summary_offset_start);
  pk.num(std::uint32_t{0});  // no CRC of the summary
  record(Op::Footer, c);
  put(kMagic, sizeof kMagic);
  std::FILE* f = f_;
  f_ = nullptr;
  if (std::fclose(f) != 0) throw std::runtime_error(path_ + ": closing (" + std::strerror(errno) + ")");
}

void Writer::write_summary_schemas() {
  std::string c;
  for (std::size_t i = 0; i < schemas_.size(); ++i) {
    c.clear();
    Packer pk{c};
    pk.num(static_cast<std::uint16_t>(i + 1));
    pk.str(schemas_[i].name);
    pk.str(schemas_[i].encoding);
    pk.str(schemas_[i].data);
    record(Op::Schema, c);
  }
}

void Writer::write_summary_channels() {
  std::string c;
  for (std::size_t i = 0; i < channels_.size(); ++i) {
    c.clear();
    Packer pk{c};
    pk.num(static_cast<std::uint16_t>(i));
    pk.num(channels_[i].schema);
    pk.str(channels_[i].topic);
    pk.str(channels_[i].encoding);
    pack_map(pk, channels_[i].metadata);
    record(Op::Channel, c);
  }
}

void Writer::write_statistics() {
  std::string c;
  Packer pk{c};
  pk.num(messages_);
  pk.num(static_cast<std::uint16_t>(schemas_.size()));
  pk.num(static_cast<std::uint32_t>(channels_.size()));
  pk.num(std::uint32_t{0});  // attachments
  pk.num(static_cast<std::uint32_t>(metadata_indexes_.size()));
  pk.num(static_cast<std::uint32_t>(chunk_indexes_.size()));
  pk.num(first_);
  pk.num(last_);
  std::string counts;
  Packer cp{counts};
  for (std::size_t i = 0; i < channel_counts_.size(); ++i) cp.num(static_cast<std::uint16_t>(i)), cp.num(channel_counts_[i]);
  pk.num(static_cast<std::uint32_t>(counts.size()));
  c += counts;
  record(Op::Statistics, c);
}

void Writer::write_chunk_indexes() {
  std::string c;
  for (const auto& ci : chunk_indexes_) {
    c.clear();
    Packer pk{c};
    pk.num(ci.start);
    pk.num(ci.end);
    pk.num(ci.offset);
    pk.num(ci.length);
    pk.num(static_cast<std::uint32_t>(ci.index_offsets.size() * 10));
    for (const auto& [ch, at] : ci.index_offsets) pk.num(ch), pk.num(at);
    pk.num(ci.index_length);
    pk.str(compression_name(opt_.compression));
    pk.num(ci.compressed);
    pk.num(ci.uncompressed);
    record(Op::ChunkIndex, c);
  }
}

void Writer::write_metadata_indexes() {
  std::string c;
  for (const auto& mi : metadata_indexes_) {
    c.clear();
    Packer pk{c};
    pk.num(mi.offset);
    pk.num(mi.length);
    pk.str(mi.name);
    record(Op::MetadataIndex, c);
  }
}

}  // namespace brickyard::mcap
