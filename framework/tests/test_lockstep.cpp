// A lockstep run's records (exec/lockstep.hpp): what crosses between processes round-trips
// exactly, and damaged bytes are refused, never read past.
#include "exec/lockstep.hpp"

#include <gtest/gtest.h>

using namespace brickyard::fw;

TEST(Lockstep, RecordsRoundTrip) {
  std::vector<LockRecord> rs(4);
  rs[0].kind = LockRecord::hello;
  rs[0].fingerprint = 0xfedcba9876543210ull;
  rs[1].seq = 123456789012ull;
  rs[1].node = 70000;
  rs[1].t_ns = 4'000'000'001;
  rs[1].pubs = {0, 3, 0, 65535};
  rs[2].t_ns = -2;  // a configure
  rs[2].stop = true;
  rs[2].result = static_cast<std::uint8_t>(RunResult::invalid_input);
  rs[2].reason = "node 'x' (p): bad \xe2\x80\x94 input";
  rs[3].kind = LockRecord::deactivated;
  rs[3].node = 5;
  rs[3].stop = true;
  rs[3].result = static_cast<std::uint8_t>(RunResult::failed);
  rs[3].reason = "did not finish";
  const auto back = decode_records(encode_records(rs));
  ASSERT_EQ(back.size(), rs.size());
  for (std::size_t i = 0; i < rs.size(); ++i) {
    EXPECT_EQ(back[i].kind, rs[i].kind);
    EXPECT_EQ(back[i].seq, rs[i].seq);
    EXPECT_EQ(back[i].node, rs[i].node);
    EXPECT_EQ(back[i].t_ns, rs[i].t_ns);
    EXPECT_EQ(back[i].pubs, rs[i].pubs);
    EXPECT_EQ(back[i].stop, rs[i].stop);
    EXPECT_EQ(back[i].result, rs[i].result);
    EXPECT_EQ(back[i].reason, rs[i].reason);
    EXPECT_EQ(back[i].fingerprint, rs[i].fingerprint);
  }
}

TEST(Lockstep, DamagedRecordsAreRefused) {
  std::vector<LockRecord> rs(1);
  rs[0].pubs = {1, 2, 3};
  rs[0].stop = true;
  rs[0].reason = "a reason";
  const auto bytes = encode_records(rs);
  // The version alone is a batch of no records; every cut inside a record is refused, none read past the end.
  EXPECT_TRUE(decode_records({bytes[0]}).empty());
  for (std::size_t n = 2; n < bytes.size(); ++n) {
    const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
    EXPECT_THROW(decode_records(cut), std::runtime_error) << n;
  }
  auto other = bytes;
  other[0] = 9;  // another version
  EXPECT_THROW(decode_records(other), std::runtime_error);
  auto kind = bytes;
  kind[1] = 77;  // no such kind
  EXPECT_THROW(decode_records(kind), std::runtime_error);
  EXPECT_THROW(decode_records({}), std::runtime_error);
}
