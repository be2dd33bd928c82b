#include "nmea0183.hpp"

#include "nmea0183_sentences.hpp"
#include "text_fields.hpp"

#include <algorithm>

namespace brickyard::drivers {

namespace {

constexpr size_t kMaxAddressBytes = 10;  // "GPGGA"; makers' "PNVGR..." are longer, still short
constexpr size_t kChecksumDigits = 2;

bool is_line_end(uint8_t c) { return c == '\r' || c == '\n'; }
bool is_address_char(uint8_t c) { return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'); }
bool is_sentence_text(uint8_t c) { return c >= 32 && c <= 126; }

}  // namespace

uint8_t nmea_checksum(std::string_view text) {
  uint8_t sum = 0;
  for (char c : text) sum ^= static_cast<uint8_t>(c);
  return sum;
}

Nmea0183Decoder::Nmea0183Decoder(NmeaDecoderLimits limits) : limits_(limits) {}

void Nmea0183Decoder::feed(const uint8_t* data, size_t size) {
  buffer_.insert(buffer_.end(), data, data + size);
  scan();
}

std::optional<NmeaMessage> Nmea0183Decoder::next() {
  if (ready_.empty()) return std::nullopt;
  NmeaMessage m = std::move(ready_.front());
  ready_.pop_front();
  return m;
}

void Nmea0183Decoder::finish() {
  scan();
  if (start_ < buffer_.size()) ++counters_.truncated;  // scan() leaves only a sentence that has begun
  buffer_.clear();
  start_ = 0;
  scanned_ = 0;
}

void Nmea0183Decoder::scan() {
  while (start_ < buffer_.size()) {
    std::optional<size_t> used = buffer_[start_] == '$' ? try_sentence(start_) : skip_garbage(start_);
    if (!used) break;
    start_ += *used;
    scanned_ = 0;
  }
  compact();
}

size_t Nmea0183Decoder::skip_garbage(size_t at) {
  size_t end = at;
  do {
    if (!is_line_end(buffer_[end])) ++counters_.skipped_bytes;
    ++end;
  } while (end < buffer_.size() && buffer_[end] != '$');
  return end - at;
}

// "$ADDRESS," then text up to '*': a line end, a non-text byte or another '$' before the '*' means
// the sentence was cut short (or came without the checksum we require).
std::optional<size_t> Nmea0183Decoder::try_sentence(size_t at) {
  size_t size = buffer_.size();
  size_t address_end = at + 1;
  while (address_end < size && is_address_char(buffer_[address_end])) {
    if (++address_end - at > kMaxAddressBytes + 1) return skip_garbage(at);
  }
  if (address_end == size) return std::nullopt;
  if (address_end == at + 1 || buffer_[address_end] != ',') return skip_garbage(at);
  size_t i = std::max(address_end, at + scanned_);
  for (; i < size; ++i) {
    if (i - at >= limits_.max_sentence_bytes) {
      ++counters_.oversized;
      return 1;  // the rest is skipped as garbage up to the next '$'
    }
    uint8_t c = buffer_[i];
    if (c == '*') {
      std::optional<size_t> used = finish_sentence(at, i);
      if (!used) scanned_ = i - at;
      return used;
    }
    if (!is_sentence_text(c) || c == '$') {
      ++counters_.truncated;
      return i - at;
    }
  }
  scanned_ = i - at;
  return std::nullopt;
}

std::optional<size_t> Nmea0183Decoder::finish_sentence(size_t at, size_t star) {
  const size_t end = star + 1 + kChecksumDigits;
  const HexCheck check = read_hex_check(buffer_, star + 1, kChecksumDigits);
  if (check.state == HexCheck::State::cut_short) {
    ++counters_.truncated;  // the checksum itself was cut short
    return check.cut_at - at;
  }
  if (check.state == HexCheck::State::incomplete) return std::nullopt;
  const unsigned stated = check.value;
  std::string_view text(reinterpret_cast<const char*>(buffer_.data() + at + 1), star - at - 1);
  if (nmea_checksum(text) != stated) {
    ++counters_.bad_checksum;
    return end - at;
  }
  NmeaMessage m;
  switch (read_sentence(text, m)) {
    case SentenceReadResult::ok: ready_.push_back(std::move(m)); ++counters_.decoded; break;
    case SentenceReadResult::unknown_sentence: ++counters_.unknown_message; break;
    case SentenceReadResult::malformed: ++counters_.malformed; break;
  }
  return end - at;
}

void Nmea0183Decoder::compact() {
  if (start_ == buffer_.size()) {
    buffer_.clear();
    start_ = 0;
  } else if (start_ > 0 && start_ >= buffer_.size() / 2) {
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(start_));
    start_ = 0;
  }
}

}  // namespace brickyard::drivers
