#include "mcap_reader.hpp"

#include "mcap_format.hpp"

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <cerrno>
#include <cstring>
#include <memory>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace brickyard::mcap {

namespace {

constexpr std::uint64_t kMaxChunk = 256ull << 20;  // bytes a chunk may claim uncompressed: past this it is damage, not an allocation (ours are 4 MiB)

std::map<std::string, std::string> unpack_map(Unpacker& u) {
  std::map<std::string, std::string> m;
  const std::uint32_t len = u.num<std::uint32_t>();
  const std::string_view body = u.bytes(len);
  Unpacker b{reinterpret_cast<const unsigned char*>(body.data()), body.size()};
  while (b.ok && b.at < b.n) {
    const std::string k(b.str());
    const std::string v(b.str());
    if (b.ok) m[k] = v;
  }
  if (!b.ok) u.ok = false;
  return m;
}

// Decompresses a chunk's records into out; an empty string, or why not.
std::string decompress(const std::string& how, std::string_view in, std::uint64_t size, std::string& out) {
  if (size > kMaxChunk) return "claims " + std::to_string(size) + " bytes uncompressed";
  out.resize(static_cast<std::size_t>(size));
  if (how.empty()) {
    if (in.size() != size) return "its records are " + std::to_string(in.size()) + " bytes, not the " + std::to_string(size) + " it says";
    std::memcpy(out.data(), in.data(), in.size());
    return {};
  }
  if (how == "zstd") {
    const std::size_t n = ZSTD_decompress(out.data(), out.size(), in.data(), in.size());
    if (ZSTD_isError(n)) return std::string("zstd: ") + ZSTD_getErrorName(n);
    if (n != size) return "decompressed to " + std::to_string(n) + " bytes, not " + std::to_string(size);
    return {};
  }
  if (how == "lz4") {
    LZ4F_dctx* ctx = nullptr;
    if (LZ4F_isError(LZ4F_createDecompressionContext(&ctx, LZ4F_VERSION))) return "lz4: no context";
    std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> guard(ctx, LZ4F_freeDecompressionContext);
    std::size_t done = 0, used_total = 0;
    while (used_total < in.size()) {
      std::size_t dst = out.size() - done, src = in.size() - used_total;
      const std::size_t r = LZ4F_decompress(ctx, out.data() + done, &dst, in.data() + used_total, &src, nullptr);
      if (LZ4F_isError(r)) return std::string("lz4: ") + LZ4F_getErrorName(r);
      done += dst;
      used_total += src;
      if (r == 0) break;
      if (src == 0 && dst == 0) return "lz4: the frame is cut short";
    }
    if (done != size) return "decompressed to " + std::to_string(done) + " bytes, not " + std::to_string(size);
    return {};
  }
  return "compression '" + how + "' is not one this reader knows (zstd, lz4)";
}

}  // namespace

// One walk through the file: what it found, and where it stopped short.
struct Reader::Scan {
  std::map<std::uint16_t, SchemaInfo>* schemas = nullptr;  // null: not collected (a second walk)
  std::map<std::uint16_t, ChannelInfo>* channels = nullptr;
  std::map<std::string, std::map<std::string, std::string>>* metadata = nullptr;
  Damage damage;

  // What the walk reads and whom it hands the messages (set by Reader::scan).
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  const std::function<void(const MessageView&)>* on_message = nullptr;
  const std::set<std::uint16_t>* only = nullptr;

  void walk();

 private:
  void damaged(std::uint64_t at, const std::string& what) { damage = {at, what}; }
  void footer(std::uint64_t at);
  void record(Op op, const Unpacker& u, std::uint64_t at, std::uint64_t len);
  void chunk_record(const Unpacker& u, std::uint64_t at, std::uint64_t len);
  bool chunk_wanted(std::uint64_t next) const;
  void chunk_records(std::uint64_t at);
  void metadata_record(const Unpacker& u, std::uint64_t at);
  bool take(Op op, Unpacker u, std::uint64_t at);
  bool take_schema(Unpacker u);
  bool take_channel(Unpacker u);
  bool take_message(Unpacker u, std::uint64_t at);

  std::string chunk_;  // the chunk at hand, decompressed (a buffer reused from chunk to chunk)
};

Reader::Reader(const std::string& path) : path_(path) {
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) throw ReadError(path + ": cannot open (" + std::strerror(errno) + ")");
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    throw ReadError(path + ": not a regular file");
  }
  size_ = static_cast<std::size_t>(st.st_size);
  if (size_ > 0) {
    void* m = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    if (m == MAP_FAILED) {
      ::close(fd);
      throw ReadError(path + ": cannot map (" + std::strerror(errno) + ")");
    }
    data_ = static_cast<const unsigned char*>(m);
  }
  ::close(fd);
  if (size_ < sizeof kMagic || std::memcmp(data_, kMagic, sizeof kMagic) != 0) {
    if (data_) ::munmap(const_cast<unsigned char*>(data_), size_);
    data_ = nullptr;
    throw ReadError(path + ": not an MCAP file (it does not begin with MCAP's magic bytes)");
  }
  Scan s;
  s.schemas = &schemas_;
  s.channels = &channels_;
  s.metadata = &metadata_;
  scan(s, nullptr, nullptr);
  damage_ = s.damage;
}

Reader::~Reader() {
  if (data_) ::munmap(const_cast<unsigned char*>(data_), size_);
}

const ChannelInfo* Reader::channel(const std::string& topic) const {
  for (const auto& [id, c] : channels_)
    if (c.topic == topic) return &c;
  return nullptr;
}

void Reader::read(const std::function<void(const MessageView&)>& on_message, const std::set<std::uint16_t>* only) const {
  Scan s;
  scan(s, &on_message, only);
}

void Reader::scan(Scan& s, const std::function<void(const MessageView&)>* on_message, const std::set<std::uint16_t>* only) const {
  s.data = data_;
  s.size = size_;
  s.on_message = on_message;
  s.only = only;
  s.walk();
}

// The data section record by record, up to its end (then the footer) or the first damage.
void Reader::Scan::walk() {
  std::uint64_t at = sizeof kMagic;
  bool first = true;
  while (damage.what.empty()) {
    if (at == size) {
      damaged(at, "the file ends without its data section's end and footer: the recording was not closed (the run killed?)");
      break;
    }
    if (size - at < 9) {
      damaged(at, "the file ends inside a record's opcode and length");
      break;
    }
    const auto op = static_cast<Op>(data[at]);
    std::uint64_t len;
    std::memcpy(&len, data + at + 1, 8);
    if (len > size - at - 9) {
      damaged(at, "a record (opcode " + std::to_string(static_cast<int>(op)) + ") of " + std::to_string(len) +
                      " bytes runs past the end of the file: truncated");
      break;
    }
    const Unpacker u{data + at + 9, static_cast<std::size_t>(len)};
    if (first && op != Op::Header) {
      damaged(at, "the first record is not the Header");
      break;
    }
    first = false;
    if (op == Op::DataEnd) return footer(at + 9 + len);
    record(op, u, at, len);
    at += 9 + len;
  }
}

// The summary is not needed (the data section said it all), but the file must end as MCAP does:
// the footer, then the magic.
void Reader::Scan::footer(std::uint64_t at) {
  const std::size_t tail = 9 + 20 + sizeof kMagic;
  if (size < at + tail || std::memcmp(data + size - sizeof kMagic, kMagic, sizeof kMagic) != 0 ||
      static_cast<Op>(data[size - tail]) != Op::Footer)
    damaged(at, "the data section ends, but the file does not end with a footer and MCAP's magic bytes: truncated");
}

// A record of the data section other than the Header's check and the Data End.
void Reader::Scan::record(Op op, const Unpacker& u, std::uint64_t at, std::uint64_t len) {
  if (op == Op::Chunk) {
    chunk_record(u, at, len);
  } else if (op == Op::Metadata) {
    metadata_record(u, at);
  } else if (!take(op, u, at)) {
    damaged(at, "a malformed record (opcode " + std::to_string(static_cast<int>(op)) + ")");
  }
}

void Reader::Scan::chunk_record(const Unpacker& u, std::uint64_t at, std::uint64_t len) {
  Unpacker c = u;
  c.num<std::uint64_t>();  // start and end times
  c.num<std::uint64_t>();
  const auto usize = c.num<std::uint64_t>();
  const auto crc = c.num<std::uint32_t>();
  const std::string how(c.str());
  const std::string_view records = c.bytes(c.num<std::uint64_t>());
  if (!c.ok) return damaged(at, "a malformed Chunk record");
  if (!chunk_wanted(at + 9 + len)) return;
  if (const std::string why = decompress(how, records, usize, chunk_); !why.empty()) {
    return damaged(at, "a chunk that does not decompress: " + why);
  }
  if (crc != 0 &&
      static_cast<std::uint32_t>(::crc32(0L, reinterpret_cast<const Bytef*>(chunk_.data()), static_cast<uInt>(chunk_.size()))) != crc) {
    return damaged(at, "a chunk whose records do not match their CRC");
  }
  chunk_records(at);
}

// The Message Index records that follow a chunk (from `next`) name its channels: skip it when none
// is wanted (and nothing is being collected).
bool Reader::Scan::chunk_wanted(std::uint64_t next) const {
  bool wanted = channels != nullptr || !only;
  if (wanted) return true;
  bool indexed = false;
  while (!wanted && size - next >= 11 && static_cast<Op>(data[next]) == Op::MessageIndex) {
    std::uint64_t ilen;
    std::memcpy(&ilen, data + next + 1, 8);
    if (ilen > size - next - 9) break;
    std::uint16_t ch;
    std::memcpy(&ch, data + next + 9, 2);
    indexed = true;
    wanted = only->count(ch) > 0;
    next += 9 + ilen;
  }
  return wanted || !indexed;
}

// The decompressed chunk's records; damage anywhere in them is the chunk's (at `at`).
void Reader::Scan::chunk_records(std::uint64_t at) {
  const auto* p = reinterpret_cast<const unsigned char*>(chunk_.data());
  for (std::size_t in = 0; in < chunk_.size() && damage.what.empty();) {
    std::uint64_t rlen = 0;
    if (chunk_.size() - in < 9 || (std::memcpy(&rlen, p + in + 1, 8), rlen > chunk_.size() - in - 9)) {
      damaged(at, "a chunk whose records run past its end (at byte " + std::to_string(in) + " of its records)");
      break;
    }
    if (!take(static_cast<Op>(p[in]), Unpacker{p + in + 9, static_cast<std::size_t>(rlen)}, at)) {
      damaged(at, "a malformed record inside a chunk (at byte " + std::to_string(in) + " of its records)");
      break;
    }
    in += 9 + rlen;
  }
}

void Reader::Scan::metadata_record(const Unpacker& u, std::uint64_t at) {
  Unpacker m = u;
  const std::string name(m.str());
  auto values = unpack_map(m);
  if (!m.ok) return damaged(at, "a malformed Metadata record");
  if (metadata)
    for (auto& [k, v] : values) (*metadata)[name][k] = v;
}

// A Schema, Channel or Message record's content (from the data section or inside a chunk).
// Returns false when it is malformed.
bool Reader::Scan::take(Op op, Unpacker u, std::uint64_t at) {
  if (op == Op::Schema && schemas) return take_schema(u);
  if (op == Op::Channel && channels) return take_channel(u);
  if (op == Op::Message) return take_message(u, at);
  return true;
}

bool Reader::Scan::take_schema(Unpacker u) {
  SchemaInfo sc;
  sc.id = u.num<std::uint16_t>();
  sc.name = u.str();
  sc.encoding = u.str();
  sc.data = u.str();
  if (!u.ok) return false;
  (*schemas)[sc.id] = std::move(sc);
  return true;
}

bool Reader::Scan::take_channel(Unpacker u) {
  ChannelInfo c;
  c.id = u.num<std::uint16_t>();
  c.schema = u.num<std::uint16_t>();
  c.topic = u.str();
  c.encoding = u.str();
  c.metadata = unpack_map(u);
  if (!u.ok) return false;
  if (!channels->count(c.id)) (*channels)[c.id] = std::move(c);
  return true;
}

// Counts the message on its channel (when collecting) and hands it on (when it is wanted).
bool Reader::Scan::take_message(Unpacker u, std::uint64_t at) {
  MessageView m;
  m.channel = u.num<std::uint16_t>();
  m.sequence = u.num<std::uint32_t>();
  m.log_time = u.num<std::uint64_t>();
  m.publish_time = u.num<std::uint64_t>();
  if (!u.ok) return false;
  m.data = u.p + u.at;
  m.size = u.n - u.at;
  if (channels) {
    auto it = channels->find(m.channel);
    if (it == channels->end()) {
      damaged(at, "a message on channel " + std::to_string(m.channel) + ", which no Channel record declared before it");
      return true;
    }
    ChannelInfo& c = it->second;
    if (c.messages == 0) c.first = c.last = m.log_time;
    c.first = std::min(c.first, m.log_time);
    c.last = std::max(c.last, m.log_time);
    ++c.messages;
    c.bytes += m.size;
  }
  if (on_message && (!only || only->count(m.channel))) (*on_message)(m);
  return true;
}

}  // namespace brickyard::mcap
