#include "cannelloni.hpp"

#include <algorithm>

namespace brickyard::vehicle_interface {

namespace {

// linux/can.h: the flags in the top three bits of can_id.
constexpr uint32_t kEffFlag = 0x80000000;
constexpr uint32_t kRtrFlag = 0x40000000;
constexpr uint32_t kErrFlag = 0x20000000;
constexpr uint8_t kFdLengthFlag = 0x80;  // cannelloni: bit 7 of the length byte marks CAN FD
constexpr size_t kMaxFramesPerDatagram = 0xFFFF;

uint32_t read_be32(const uint8_t* p) {
  return uint32_t{p[0]} << 24 | uint32_t{p[1]} << 16 | uint32_t{p[2]} << 8 | uint32_t{p[3]};
}

size_t encoded_size(const CanFrame& f) { return 5 + (f.fd ? 1 : 0) + (f.remote ? 0 : f.length); }

void append_frame(const CanFrame& f, std::vector<uint8_t>& out) {
  const uint32_t can_id = f.id | (f.extended ? kEffFlag : 0) | (f.remote ? kRtrFlag : 0);
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<uint8_t>(can_id >> shift));
  out.push_back(static_cast<uint8_t>(f.length | (f.fd ? kFdLengthFlag : 0)));
  if (f.fd) out.push_back(f.fd_flags);
  if (!f.remote) out.insert(out.end(), f.data.begin(), f.data.begin() + f.length);
}

struct ParsedFrame {
  CanFrame frame;
  bool error_frame = false;
  size_t end = 0;  // where the next frame starts
};

// One frame at `at`: its header, then its data. kNone with `out` filled, or why not.
CannelloniRefusal parse_frame(const uint8_t* d, size_t size, size_t at, ParsedFrame& out) {
  if (size - at < 5) return CannelloniRefusal::kTruncatedFrame;
  const uint32_t can_id = read_be32(d + at);
  const uint8_t length_byte = d[at + 4];
  at += 5;
  CanFrame& f = out.frame;
  f.fd = (length_byte & kFdLengthFlag) != 0;
  f.length = length_byte & static_cast<uint8_t>(~kFdLengthFlag);
  if (f.fd) {
    if (at == size) return CannelloniRefusal::kTruncatedFrame;
    f.fd_flags = d[at++];
  }
  f.extended = (can_id & kEffFlag) != 0;
  f.remote = (can_id & kRtrFlag) != 0;
  f.id = can_id & kExtendedIdMax;
  out.error_frame = (can_id & kErrFlag) != 0;
  if (!f.extended && f.id > kStandardIdMax) return CannelloniRefusal::kBadId;
  if (f.fd ? (f.remote || !is_fd_length(f.length)) : f.length > kClassicMaxBytes) return CannelloniRefusal::kBadLength;
  const size_t data_bytes = f.remote ? 0 : f.length;
  if (size - at < data_bytes) return CannelloniRefusal::kTruncatedFrame;
  std::copy(d + at, d + at + data_bytes, f.data.begin());
  out.end = at + data_bytes;
  return CannelloniRefusal::kNone;
}

}  // namespace

const char* refusal_name(CannelloniRefusal refusal) {
  switch (refusal) {
    case CannelloniRefusal::kNone: return "none";
    case CannelloniRefusal::kShortDatagram: return "short datagram";
    case CannelloniRefusal::kBadVersion: return "bad version";
    case CannelloniRefusal::kBadOpCode: return "bad op code";
    case CannelloniRefusal::kTruncatedFrame: return "truncated frame";
    case CannelloniRefusal::kBadLength: return "bad length";
    case CannelloniRefusal::kBadId: return "bad id";
    case CannelloniRefusal::kTrailingBytes: return "trailing bytes";
  }
  return "unknown";
}

void CannelloniCounters::count(CannelloniRefusal refusal) {
  switch (refusal) {
    case CannelloniRefusal::kNone: break;
    case CannelloniRefusal::kShortDatagram: ++short_datagram; break;
    case CannelloniRefusal::kBadVersion: ++bad_version; break;
    case CannelloniRefusal::kBadOpCode: ++bad_op_code; break;
    case CannelloniRefusal::kTruncatedFrame: ++truncated_frame; break;
    case CannelloniRefusal::kBadLength: ++bad_length; break;
    case CannelloniRefusal::kBadId: ++bad_id; break;
    case CannelloniRefusal::kTrailingBytes: ++trailing_bytes; break;
  }
}

CannelloniRefusal CannelloniDecoder::decode(const uint8_t* d, size_t size, std::vector<CanFrame>& frames) {
  ++counters_.datagrams;
  auto refuse = [&](CannelloniRefusal why) {
    counters_.count(why);
    return why;
  };
  if (size < kCannelloniHeaderBytes) return refuse(CannelloniRefusal::kShortDatagram);
  if (d[0] != kCannelloniVersion) return refuse(CannelloniRefusal::kBadVersion);
  if (d[1] != kCannelloniOpData) return refuse(CannelloniRefusal::kBadOpCode);
  const size_t count = size_t{d[3]} << 8 | d[4];
  std::vector<CanFrame> accepted;
  accepted.reserve(std::min(count, size / 5));  // a frame takes 5 bytes at least: the count cannot inflate this
  uint64_t error_frames = 0;
  size_t at = kCannelloniHeaderBytes;
  for (size_t i = 0; i < count; ++i) {
    ParsedFrame parsed;
    if (const CannelloniRefusal why = parse_frame(d, size, at, parsed); why != CannelloniRefusal::kNone) return refuse(why);
    at = parsed.end;
    if (parsed.error_frame) ++error_frames;
    else accepted.push_back(parsed.frame);
  }
  if (at != size) return refuse(CannelloniRefusal::kTrailingBytes);
  last_sequence_ = d[2];
  counters_.frames += accepted.size();
  counters_.error_frames += error_frames;
  frames.insert(frames.end(), accepted.begin(), accepted.end());
  return CannelloniRefusal::kNone;
}

CannelloniEncoding encode_cannelloni(const std::vector<CanFrame>& frames, uint8_t& sequence, size_t max_datagram_bytes) {
  CannelloniEncoding out;
  for (size_t i = 0; i < frames.size(); ++i) {
    if (std::string problem = frame_problem(frames[i]); !problem.empty()) {
      out.error = "frame " + std::to_string(i) + ": " + problem;
      return out;
    }
  }
  size_t next = 0;
  while (next < frames.size()) {
    std::vector<uint8_t> datagram = {kCannelloniVersion, kCannelloniOpData, sequence++, 0, 0};
    size_t count = 0;
    while (next < frames.size() && count < kMaxFramesPerDatagram &&
           (count == 0 || datagram.size() + encoded_size(frames[next]) <= max_datagram_bytes)) {
      append_frame(frames[next++], datagram);
      ++count;
    }
    datagram[3] = static_cast<uint8_t>(count >> 8);
    datagram[4] = static_cast<uint8_t>(count);
    out.datagrams.push_back(std::move(datagram));
  }
  return out;
}

}  // namespace brickyard::vehicle_interface
