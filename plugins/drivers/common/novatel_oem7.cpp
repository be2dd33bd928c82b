#include "novatel_oem7.hpp"

#include "oem7_ascii.hpp"
#include "oem7_binary.hpp"
#include "oem7_crc.hpp"
#include "text_fields.hpp"

#include <algorithm>

namespace brickyard::drivers {

namespace {

constexpr size_t kMaxLogNameBytes = 40;  // "BESTPOSA" and kin; a longer run of capitals is no log's name
constexpr size_t kAsciiCrcDigits = 8;
constexpr uint8_t kResponseBit = 0x80;   // message type bit 7: a reply to a command, not a log
constexpr uint8_t kFormatBits = 0x60;    // message type bits 5-6: 00 binary, 01 ASCII, 10 abbreviated

uint16_t u16_at(const uint8_t* p) { return static_cast<uint16_t>(p[0] | p[1] << 8); }
uint32_t u32_at(const uint8_t* p) {
  return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 | static_cast<uint32_t>(p[2]) << 16 |
         static_cast<uint32_t>(p[3]) << 24;
}

bool starts_a_log(uint8_t b) { return b == kOem7Sync0 || b == '#' || b == '%'; }
bool is_line_end(uint8_t c) { return c == '\r' || c == '\n'; }
bool is_name_char(uint8_t c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'; }
// What an ASCII log may hold before its '*': printable characters and tabs (OEM7 "ASCII" page).
bool is_log_text(uint8_t c) { return (c >= 32 && c <= 126) || c == '\t'; }

// A binary sync inside a frame whose CRC failed: the log was cut short and the next one follows.
bool holds_binary_sync(const uint8_t* from, const uint8_t* to) {
  for (const uint8_t* p = from; p + 2 < to; ++p)
    if (p[0] == kOem7Sync0 && p[1] == kOem7Sync1 && (p[2] == kOem7SyncLong || p[2] == kOem7SyncShort)) return true;
  return false;
}

template <typename Message>
bool read_binary_message(const Oem7Header& header, const uint8_t* body, size_t body_bytes, std::deque<Oem7Message>& ready) {
  Message m;
  m.header = header;
  if (!read_body(std::span(body, body_bytes), m)) return false;
  ready.push_back(std::move(m));
  return true;
}

void append_crc(std::vector<uint8_t>& bytes) {
  uint32_t crc = oem7_crc32(bytes.data(), bytes.size());
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<uint8_t>(crc >> (8 * i)));
}

template <typename Message>
std::vector<uint8_t> encode_long_header(const Message& m, uint16_t message_id) {
  std::vector<uint8_t> body, bytes;
  write_body(m, body);
  write_binary_header(m.header, message_id, static_cast<uint16_t>(body.size()), bytes);
  bytes.insert(bytes.end(), body.begin(), body.end());
  append_crc(bytes);
  return bytes;
}

}  // namespace

NovatelOem7Decoder::NovatelOem7Decoder(Oem7DecoderLimits limits) : limits_(limits) {}

void NovatelOem7Decoder::feed(const uint8_t* data, size_t size) {
  buffer_.insert(buffer_.end(), data, data + size);
  scan();
}

std::optional<Oem7Message> NovatelOem7Decoder::next() {
  if (ready_.empty()) return std::nullopt;
  Oem7Message m = std::move(ready_.front());
  ready_.pop_front();
  return m;
}

// scan() leaves only a log that has begun: the stream's end cut it (one log at most: any earlier
// cut was found by what followed it). Its first byte is dropped and the rest read on, since a cut
// binary log's length field may have claimed whole logs behind it; what stays incomplete after
// that is the cut log's remains, skipped.
void NovatelOem7Decoder::finish() {
  scan();
  if (start_ < buffer_.size()) ++counters_.truncated;
  for (bool first = true; start_ < buffer_.size(); first = false) {
    if (!first) ++counters_.skipped_bytes;
    ++start_;
    ascii_scanned_ = 0;
    ascii_in_quotes_ = false;
    scan();
  }
  buffer_.clear();
  start_ = 0;
}

// Consumes every log and every run of garbage it can; stops at a log still arriving.
void NovatelOem7Decoder::scan() {
  while (start_ < buffer_.size()) {
    std::optional<size_t> used = try_frame(start_);
    if (!used) break;
    start_ += *used;
    ascii_scanned_ = 0;
    ascii_in_quotes_ = false;
  }
  compact();
}

std::optional<size_t> NovatelOem7Decoder::try_frame(size_t at) {
  uint8_t b = buffer_[at];
  if (b == kOem7Sync0) return try_binary(at);
  if (b == '#' || b == '%') return try_ascii(at);
  return skip_garbage(at);
}

// The byte at `at` and those after it up to the next possible sync.
size_t NovatelOem7Decoder::skip_garbage(size_t at) {
  size_t end = at;
  do {
    if (!is_line_end(buffer_[end])) ++counters_.skipped_bytes;
    ++end;
  } while (end < buffer_.size() && !starts_a_log(buffer_[end]));
  return end - at;
}

std::optional<size_t> NovatelOem7Decoder::try_binary(size_t at) {
  size_t available = buffer_.size() - at;
  const uint8_t* p = buffer_.data() + at;
  if (available >= 2 && p[1] != kOem7Sync1) return skip_garbage(at);
  if (available < 3) return std::nullopt;
  if (p[2] == kOem7SyncLong) return try_binary_long(at);
  if (p[2] == kOem7SyncShort) return try_binary_short(at);
  return skip_garbage(at);
}

// Refusals before the CRC consume only the first sync byte, so a real log behind a false sync is
// still found; a log whose CRC passed is consumed whole.
std::optional<size_t> NovatelOem7Decoder::try_binary_long(size_t at) {
  size_t available = buffer_.size() - at;
  if (available < 10) return std::nullopt;  // header length (byte 3) and message length (bytes 8-9)
  const uint8_t* p = buffer_.data() + at;
  size_t header_bytes = p[3];
  size_t body_bytes = u16_at(p + 8);
  if (header_bytes < kOem7HeaderBytes) {
    ++counters_.malformed;
    return 1;
  }
  if (body_bytes > limits_.max_binary_body_bytes) {
    ++counters_.oversized;
    return 1;
  }
  size_t frame = header_bytes + body_bytes + kOem7CrcBytes;
  if (available < frame) return std::nullopt;
  if (oem7_crc32(p, header_bytes + body_bytes) != u32_at(p + header_bytes + body_bytes)) return refuse_binary_crc(at, frame);
  uint8_t message_type = p[6];
  if (message_type & kResponseBit) ++counters_.unknown_message;
  else if (message_type & kFormatBits) ++counters_.malformed;  // a binary frame claiming to be text
  else accept_binary(u16_at(p + 4), read_binary_header(p), p + header_bytes, body_bytes);
  return frame;
}

std::optional<size_t> NovatelOem7Decoder::try_binary_short(size_t at) {
  size_t available = buffer_.size() - at;
  if (available < kOem7ShortHeaderBytes) return std::nullopt;
  const uint8_t* p = buffer_.data() + at;
  size_t body_bytes = p[3];
  size_t frame = kOem7ShortHeaderBytes + body_bytes + kOem7CrcBytes;
  if (available < frame) return std::nullopt;
  size_t covered = kOem7ShortHeaderBytes + body_bytes;
  if (oem7_crc32(p, covered) != u32_at(p + covered)) return refuse_binary_crc(at, frame);
  accept_binary(u16_at(p + 4), read_binary_short_header(p), p + kOem7ShortHeaderBytes, body_bytes);
  return frame;
}

size_t NovatelOem7Decoder::refuse_binary_crc(size_t at, size_t frame_bytes) {
  const uint8_t* p = buffer_.data() + at;
  if (holds_binary_sync(p + 1, p + frame_bytes)) ++counters_.truncated;
  else ++counters_.bad_checksum;
  return 1;
}

void NovatelOem7Decoder::accept_binary(uint16_t message_id, const Oem7Header& header, const uint8_t* body, size_t body_bytes) {
  bool read = false;
  switch (message_id) {
    case kBestPosId: read = read_binary_message<BestPos>(header, body, body_bytes, ready_); break;
    case kBestVelId: read = read_binary_message<BestVel>(header, body, body_bytes, ready_); break;
    case kInsPvaXId: read = read_binary_message<InsPvaX>(header, body, body_bytes, ready_); break;
    case kRawImuSXId: read = read_binary_message<RawImuSX>(header, body, body_bytes, ready_); break;
    default: ++counters_.unknown_message; return;
  }
  if (read) ++counters_.decoded;
  else ++counters_.malformed;  // shorter than the documented layout
}

// "#NAME," or "%NAME," then text up to '*': a line end, a non-text byte or the next sync before
// the '*' means the log was cut short.
std::optional<size_t> NovatelOem7Decoder::try_ascii(size_t at) {
  size_t size = buffer_.size();
  size_t name_end = at + 1;
  while (name_end < size && is_name_char(buffer_[name_end])) {
    if (++name_end - at > kMaxLogNameBytes) return skip_garbage(at);
  }
  if (name_end == size) return std::nullopt;
  if (name_end == at + 1 || (buffer_[name_end] != ',' && buffer_[name_end] != ';')) return skip_garbage(at);
  size_t i = std::max(name_end, at + ascii_scanned_);
  for (; i < size; ++i) {
    if (i - at >= limits_.max_ascii_log_bytes) {
      ++counters_.oversized;
      return 1;  // the rest is skipped as garbage up to the next sync
    }
    uint8_t c = buffer_[i];
    if (c == '"') {
      ascii_in_quotes_ = !ascii_in_quotes_;
    } else if (c == '*' && !ascii_in_quotes_) {
      std::optional<size_t> used = finish_ascii(at, i);
      if (!used) ascii_scanned_ = i - at;  // resume at the '*' when the CRC's digits arrive
      return used;
    } else if (!is_log_text(c) || (!ascii_in_quotes_ && (c == '#' || c == '%'))) {
      ++counters_.truncated;
      return i - at;
    }
  }
  ascii_scanned_ = i - at;
  return std::nullopt;
}

std::optional<size_t> NovatelOem7Decoder::finish_ascii(size_t at, size_t star) {
  const size_t end = star + 1 + kAsciiCrcDigits;
  const HexCheck check = read_hex_check(buffer_, star + 1, kAsciiCrcDigits);
  if (check.state == HexCheck::State::cut_short) {
    ++counters_.truncated;  // the CRC itself was cut short
    return check.cut_at - at;
  }
  if (check.state == HexCheck::State::incomplete) return std::nullopt;
  const uint32_t stated = check.value;
  const uint8_t* text = buffer_.data() + at + 1;
  size_t text_bytes = star - at - 1;
  if (oem7_crc32(text, text_bytes) != stated) {
    ++counters_.bad_checksum;
    return end - at;
  }
  Oem7Message m;
  switch (read_ascii_log({reinterpret_cast<const char*>(text), text_bytes}, buffer_[at] == '%', m)) {
    case AsciiReadResult::ok: ready_.push_back(std::move(m)); ++counters_.decoded; break;
    case AsciiReadResult::unknown_message: ++counters_.unknown_message; break;
    case AsciiReadResult::malformed: ++counters_.malformed; break;
  }
  return end - at;
}

void NovatelOem7Decoder::compact() {
  if (start_ == buffer_.size()) {
    buffer_.clear();
    start_ = 0;
  } else if (start_ > 0 && start_ >= buffer_.size() / 2) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
}

std::vector<uint8_t> encode_oem7_binary(const BestPos& m) { return encode_long_header(m, kBestPosId); }
std::vector<uint8_t> encode_oem7_binary(const BestVel& m) { return encode_long_header(m, kBestVelId); }
std::vector<uint8_t> encode_oem7_binary(const InsPvaX& m) { return encode_long_header(m, kInsPvaXId); }

std::vector<uint8_t> encode_oem7_binary(const RawImuSX& m) {
  std::vector<uint8_t> body, bytes;
  write_body(m, body);
  write_binary_short_header(m.header, kRawImuSXId, static_cast<uint8_t>(body.size()), bytes);
  bytes.insert(bytes.end(), body.begin(), body.end());
  append_crc(bytes);
  return bytes;
}

std::vector<uint8_t> encode_oem7_binary(const Oem7Message& m) {
  return std::visit([](const auto& message) { return encode_oem7_binary(message); }, m);
}

}  // namespace brickyard::drivers
