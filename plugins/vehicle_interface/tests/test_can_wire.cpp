// CAN frames on the wire: can-utils' candump log lines (the examples of can-utils' lib.h and
// lines written by hand) and cannelloni's UDP datagrams (its doc/udp_format.md, bytes laid out
// by hand below). Every refusal is asserted by its reason and line.
#include "vehicle_interface/common/candump_log.hpp"
#include "vehicle_interface/common/cannelloni.hpp"

#include "can_frames.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace brickyard::vehicle_interface;

namespace {

CandumpRecord parsed(const std::string& line) {
  const CandumpLine l = parse_candump_line(line);
  EXPECT_TRUE(l.record.has_value()) << line << ": " << l.error;
  return l.record.value_or(CandumpRecord{});
}

std::string line_error(const std::string& line) { return parse_candump_line(line).error; }

// Frames of every kind, ids, lengths and bytes drawn with a fixed seed.
std::vector<CanFrame> random_frames(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::vector<CanFrame> frames;
  static const uint8_t kFdLengths[] = {0, 1, 5, 8, 12, 16, 20, 24, 32, 48, 64};
  for (size_t i = 0; i < n; ++i) {
    CanFrame f;
    f.extended = rng() % 2;
    f.id = rng() & (f.extended ? kExtendedIdMax : kStandardIdMax);
    const uint32_t kind = rng() % 4;
    f.fd = kind == 3;
    f.remote = kind == 2;
    f.length = static_cast<uint8_t>(f.fd ? kFdLengths[rng() % 11] : rng() % 9);
    if (f.fd) f.fd_flags = static_cast<uint8_t>(rng() % 4);
    if (!f.remote)
      for (size_t b = 0; b < f.length; ++b) f.data[b] = static_cast<uint8_t>(rng());
    frames.push_back(f);
  }
  return frames;
}

}  // namespace

TEST(Candump, ReadsEachKindOfLine) {
  CandumpRecord r = parsed("(1436509052.249713) can0 123#DEADBEEF");
  EXPECT_EQ(r.seconds, 1436509052u);
  EXPECT_EQ(r.microseconds, 249713u);
  EXPECT_EQ(r.interface, "can0");
  EXPECT_EQ(r.frame, frame_of(0x123, {0xDE, 0xAD, 0xBE, 0xEF}));

  EXPECT_EQ(parsed("(0000000001.000002) vcan1 12345678#0011").frame, frame_of(0x12345678, {0x00, 0x11}, true));
  EXPECT_EQ(parsed("(1.000000) can0 123#").frame, frame_of(0x123, {}));
  EXPECT_EQ(parsed("(1.000000) can0 123#11.22.33.44.55.66.77.88").frame,
            frame_of(0x123, {0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88}));
  EXPECT_EQ(parsed("(1.000000) can0 123#11.2233.44556677.88\r").frame,  // lib.h's example, a CRLF line
            frame_of(0x123, {0x11, 0x22, 0x33, 0x44, 0x55, 0x66, 0x77, 0x88}));
  EXPECT_EQ(parsed("(1.000000) can0 7a1#deadbeef").frame, frame_of(0x7A1, {0xDE, 0xAD, 0xBE, 0xEF}));

  CanFrame remote = frame_of(0x123, {});
  remote.remote = true;
  EXPECT_EQ(parsed("(1.000000) can0 123#R").frame, remote);
  remote.length = 7;
  EXPECT_EQ(parsed("(1.000000) can0 123#R7").frame, remote);

  CanFrame fd = frame_of(0x123, {0x11, 0x22, 0x33});
  fd.fd = true;
  fd.fd_flags = kFdBitRateSwitch;
  EXPECT_EQ(parsed("(1.000000) can0 123##1112233").frame, fd);
}

TEST(Candump, RefusesBadLinesSayingWhy) {
  EXPECT_EQ(line_error("(1.5) can0 123#00"), "timestamp is not (seconds.microseconds)");
  EXPECT_EQ(line_error("(12345.5000) can0 123#00"), "timestamp is not (seconds.microseconds), 6 digits after the point");
  EXPECT_EQ(line_error("1.500000 can0 123#00"), "timestamp is not (seconds.microseconds)");
  EXPECT_EQ(line_error("(1.50000x) can0 123#00"), "timestamp has a character other than digits");
  EXPECT_EQ(line_error("(1.000000) can0"), "line is not (time) interface frame");
  EXPECT_EQ(line_error("(1.000000) can0 123#00 extra"), "line is not (time) interface frame");
  EXPECT_EQ(line_error("(1.000000) can0 1234#00"), "id is not 3 or 8 hex digits");
  EXPECT_EQ(line_error("(1.000000) can0 12G#00"), "id is not hex digits");
  EXPECT_EQ(line_error("(1.000000) can0 800#00"), "id over 7FF");
  EXPECT_EQ(line_error("(1.000000) can0 1234567#00"), "id is not 3 or 8 hex digits");
  EXPECT_EQ(line_error("(1.000000) can0 123#0"), "data is not pairs of hex digits");
  EXPECT_EQ(line_error("(1.000000) can0 123#.00"), "data is not pairs of hex digits");
  EXPECT_EQ(line_error("(1.000000) can0 123#001122334455667788"), "more than 8 data bytes");
  EXPECT_EQ(line_error("(1.000000) can0 123#R9"), "remote frame's length is not one digit 0 to 8");
  EXPECT_EQ(line_error("(1.000000) can0 123##"), "CAN FD frame without its flags digit");
  EXPECT_EQ(line_error("(1.000000) can0 123##0112233445566778899"), "9 bytes is not a CAN FD length");
  EXPECT_EQ(line_error("(1.000000) can0 123"), "frame is not id#data");
  EXPECT_EQ(line_error("(1.000000) averyveryverylongname 123#00"), "interface name longer than 15 characters");
}

TEST(Candump, ReadsALogNamingBadLinesAndCountingErrorFrames) {
  const std::string text =
      "(1436509052.249713) can0 123#DEADBEEF\n"
      "\n"
      "(1436509052.249800) can0 123#DEADBEE\n"                // line 3: odd digits
      "(1436509052.250000) can0 20000080#0000080000000000\n"  // line 4: an error frame (CAN_ERR_FLAG)
      "garbage\n"                                             // line 5
      "(1436509052.251000) can1 1FFFFFFF#R\r\n";
  const CandumpLog log = read_candump(text);
  ASSERT_EQ(log.records.size(), 2u);
  EXPECT_EQ(log.records[1].frame.id, 0x1FFFFFFFu);
  EXPECT_TRUE(log.records[1].frame.remote);
  EXPECT_EQ(log.error_frames, 1u);
  EXPECT_EQ(log.bad_lines, 2u);
  ASSERT_EQ(log.errors.size(), 2u);
  EXPECT_EQ(log.errors[0].text(), "line 3: data is not pairs of hex digits");
  EXPECT_EQ(log.errors[1].text(), "line 5: line is not (time) interface frame");

  // Lines over 40 bytes refused too: lines 4 (50 bytes) and 7 (45) join lines 3 and 5.
  CandumpLimits limits;
  limits.max_errors = 1;
  limits.max_line_bytes = 40;
  const CandumpLog bounded = read_candump(text + "(1436509052.251000) can1 123#0011223344556677\n", limits);
  EXPECT_EQ(bounded.bad_lines, 4u);
  EXPECT_EQ(bounded.error_frames, 0u);
  ASSERT_EQ(bounded.errors.size(), 1u);
  EXPECT_EQ(bounded.records.size(), 2u);
}

TEST(Candump, WritesWhatItReadsAndReadsWhatItWrites) {
  const std::string canonical =
      "(1436509052.249713) can0 123#DEADBEEF\n"
      "(1436509052.249714) can0 12345678#\n"
      "(1436509052.249715) can1 123#R\n"
      "(1436509052.249716) can1 0000ABCD#R8\n"
      "(1436509052.249717) can0 7FF##3000102030405060708090A0B\n";
  const CandumpLog log = read_candump(canonical);
  ASSERT_EQ(log.records.size(), 5u);
  EXPECT_TRUE(log.errors.empty());
  EXPECT_EQ(write_candump(log.records), canonical);

  std::vector<CandumpRecord> records;
  uint64_t micros = 0;
  for (const CanFrame& f : random_frames(500, 7)) {
    records.push_back({1700000000 + micros / 1000000, static_cast<uint32_t>(micros % 1000000), "can0", f});
    micros += 1234;
  }
  const CandumpLog back = read_candump(write_candump(records));
  EXPECT_TRUE(back.errors.empty());
  EXPECT_EQ(back.records, records);

  const std::string path = testing::TempDir() + "/brickyard_candump_test.log";
  std::string error;
  ASSERT_TRUE(save_candump_file(path, records, &error)) << error;
  EXPECT_EQ(load_candump_file(path).records, records);
  std::remove(path.c_str());
  EXPECT_EQ(load_candump_file(path).errors.front().text(), "line 0: " + path + ": cannot be opened (No such file or directory)");
  EXPECT_EQ(load_candump_file("/dev/zero").errors.front().text(), "line 0: /dev/zero: not a regular file");
}

// Datagrams laid out by hand from cannelloni's doc/udp_format.md: version 2, op code 0 (DATA),
// sequence, count (big-endian 16 bits), then per frame can_id (big-endian, linux/can.h flags in
// bits 29..31), len (bit 7: CAN FD, then a flags byte), data (none for a remote request).
TEST(Cannelloni, EncodesFramesAsTheFormatLaysThemOut) {
  CanFrame remote = frame_of(0x18FEF1FE, {}, true);
  remote.remote = true;
  remote.length = 8;
  CanFrame fd = frame_of(0x100, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12});
  fd.fd = true;
  fd.fd_flags = kFdBitRateSwitch;
  uint8_t sequence = 7;
  const CannelloniEncoding e = encode_cannelloni({frame_of(0x123, {0xDE, 0xAD}), remote, fd}, sequence);
  ASSERT_TRUE(e.error.empty()) << e.error;
  ASSERT_EQ(e.datagrams.size(), 1u);
  const std::vector<uint8_t> expected = {
      0x02, 0x00, 0x07, 0x00, 0x03,                    // version 2, DATA, sequence 7, 3 frames
      0x00, 0x00, 0x01, 0x23, 0x02, 0xDE, 0xAD,        // 0x123, 2 bytes
      0xD8, 0xFE, 0xF1, 0xFE, 0x08,                    // EFF|RTR|0x18FEF1FE, length 8, no data
      0x00, 0x00, 0x01, 0x00, 0x8C, 0x01,              // 0x100, CAN FD (0x80) | 12, flags BRS
      1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  EXPECT_EQ(e.datagrams[0], expected);
  EXPECT_EQ(sequence, 8);

  CannelloniDecoder decoder;
  std::vector<CanFrame> frames;
  EXPECT_EQ(decoder.decode(expected.data(), expected.size(), frames), CannelloniRefusal::kNone);
  EXPECT_EQ(frames, (std::vector<CanFrame>{frame_of(0x123, {0xDE, 0xAD}), remote, fd}));
  EXPECT_EQ(decoder.last_sequence(), 7);
}

TEST(Cannelloni, RoundTripsRandomFramesSplitOverDatagrams) {
  const std::vector<CanFrame> frames = random_frames(2000, 11);
  uint8_t sequence = 250;
  const CannelloniEncoding e = encode_cannelloni(frames, sequence, 200);
  ASSERT_TRUE(e.error.empty()) << e.error;
  CannelloniDecoder decoder;
  std::vector<CanFrame> back;
  uint8_t expected_sequence = 250;
  for (const std::vector<uint8_t>& d : e.datagrams) {
    EXPECT_LE(d.size(), 200u);
    EXPECT_EQ(decoder.decode(d.data(), d.size(), back), CannelloniRefusal::kNone);
    EXPECT_EQ(decoder.last_sequence(), expected_sequence++);  // wraps past 255
  }
  EXPECT_EQ(back, frames);
  EXPECT_EQ(sequence, static_cast<uint8_t>(250 + e.datagrams.size()));
  EXPECT_EQ(decoder.counters().frames, 2000u);
  EXPECT_EQ(decoder.counters().refused(), 0u);
}

TEST(Cannelloni, RefusesBrokenDatagramsWholeCountingEachReason) {
  struct Case {
    std::vector<uint8_t> bytes;
    CannelloniRefusal why;
  };
  const std::vector<Case> cases = {
      {{0x02, 0x00, 0x00, 0x00}, CannelloniRefusal::kShortDatagram},
      {{0x01, 0x00, 0x00, 0x00, 0x00}, CannelloniRefusal::kBadVersion},
      {{0x02, 0x01, 0x00, 0x00, 0x00}, CannelloniRefusal::kBadOpCode},
      // count 2, one whole frame: the second is missing.
      {{0x02, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x01, 0x23, 0x01, 0xAA}, CannelloniRefusal::kTruncatedFrame},
      // a frame whose 4 data bytes are cut to 2.
      {{0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x01, 0x23, 0x04, 0xAA, 0xBB}, CannelloniRefusal::kTruncatedFrame},
      // a CAN FD frame cut before its flags byte.
      {{0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x01, 0x23, 0x80}, CannelloniRefusal::kTruncatedFrame},
      // classic length 9.
      {{0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x01, 0x23, 0x09, 1, 2, 3, 4, 5, 6, 7, 8, 9}, CannelloniRefusal::kBadLength},
      // CAN FD length 10 (0x8A): not a CAN FD length.
      {{0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x01, 0x23, 0x8A, 0x00, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, CannelloniRefusal::kBadLength},
      // a remote CAN FD frame.
      {{0x02, 0x00, 0x00, 0x00, 0x01, 0x40, 0x00, 0x01, 0x23, 0x80, 0x00}, CannelloniRefusal::kBadLength},
      // an 11-bit frame with id 0x800.
      {{0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x08, 0x00, 0x00}, CannelloniRefusal::kBadId},
      // a whole frame and a byte more.
      {{0x02, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x01, 0x23, 0x00, 0xFF}, CannelloniRefusal::kTrailingBytes},
  };
  CannelloniDecoder decoder;
  std::vector<CanFrame> frames;
  for (const Case& c : cases)
    EXPECT_EQ(decoder.decode(c.bytes.data(), c.bytes.size(), frames), c.why) << refusal_name(c.why);
  EXPECT_TRUE(frames.empty());
  const CannelloniCounters& n = decoder.counters();
  EXPECT_EQ(n.datagrams, 11u);
  EXPECT_EQ(n.frames, 0u);
  EXPECT_EQ(n.short_datagram, 1u);
  EXPECT_EQ(n.bad_version, 1u);
  EXPECT_EQ(n.bad_op_code, 1u);
  EXPECT_EQ(n.truncated_frame, 3u);
  EXPECT_EQ(n.bad_length, 3u);
  EXPECT_EQ(n.bad_id, 1u);
  EXPECT_EQ(n.trailing_bytes, 1u);
  EXPECT_EQ(n.refused(), 11u);
  EXPECT_STREQ(refusal_name(CannelloniRefusal::kTruncatedFrame), "truncated frame");
}

TEST(Cannelloni, PassesOverErrorFramesAndEmptyDatagrams) {
  // An error frame (CAN_ERR_FLAG 0x20000000, 8 data bytes) between two data frames.
  const std::vector<uint8_t> d = {0x02, 0x00, 0x05, 0x00, 0x03,
                                  0x00, 0x00, 0x01, 0x23, 0x01, 0xAA,
                                  0x20, 0x00, 0x00, 0x04, 0x08, 0, 0, 0, 0, 0, 0, 0, 0,
                                  0x00, 0x00, 0x03, 0x21, 0x00};
  CannelloniDecoder decoder;
  std::vector<CanFrame> frames;
  EXPECT_EQ(decoder.decode(d.data(), d.size(), frames), CannelloniRefusal::kNone);
  EXPECT_EQ(frames, (std::vector<CanFrame>{frame_of(0x123, {0xAA}), frame_of(0x321, {})}));
  EXPECT_EQ(decoder.counters().error_frames, 1u);
  const std::vector<uint8_t> empty = {0x02, 0x00, 0x06, 0x00, 0x00};
  EXPECT_EQ(decoder.decode(empty.data(), empty.size(), frames), CannelloniRefusal::kNone);
  EXPECT_EQ(frames.size(), 2u);
  EXPECT_EQ(decoder.last_sequence(), 6);
}

TEST(Cannelloni, RefusesToEncodeFramesNoBusCarries) {
  uint8_t sequence = 0;
  EXPECT_EQ(encode_cannelloni({frame_of(0x800, {})}, sequence).error, "frame 0: id wider than 11 bits");
  CanFrame long_classic = frame_of(0x1, std::vector<uint8_t>(9));
  EXPECT_EQ(encode_cannelloni({frame_of(0x1, {}), long_classic}, sequence).error, "frame 1: length 9 over 8 bytes");
  CanFrame fd = frame_of(0x1, std::vector<uint8_t>(10));
  fd.fd = true;
  EXPECT_EQ(encode_cannelloni({fd}, sequence).error, "frame 0: length 10 is not a CAN FD length");
  EXPECT_EQ(sequence, 0);
  EXPECT_TRUE(encode_cannelloni({}, sequence).datagrams.empty());
}
