// A split run's end records (exec/peer_ends.hpp): what a process says of its end round-trips, and
// bytes that are not one are refused, never taken as a verdict.
#include "exec/peer_ends.hpp"

#include <gtest/gtest.h>

#include <string>

using namespace brickyard::fw;

namespace {
std::vector<std::uint8_t> bytes(const std::string& s) { return {s.begin(), s.end()}; }
}  // namespace

TEST(PeerEnds, AnEndRoundTrips) {
  for (RunResult r : {RunResult::success, RunResult::failed, RunResult::interrupted, RunResult::invalid_input}) {
    const PeerEnd in{r, "node 'src' (testing.fault) failed in step: \"quoted\" \xe2\x80\x94 and a\nnewline"};
    const std::optional<PeerEnd> out = decode_end(encode_end(in));
    ASSERT_TRUE(out);
    EXPECT_EQ(out->result, r);
    EXPECT_EQ(out->reason, in.reason);
  }
}

TEST(PeerEnds, BytesThatAreNotAnEndAreRefused) {
  EXPECT_FALSE(decode_end({}));
  EXPECT_FALSE(decode_end(bytes("{\"result\": \"failed\"")));                       // cut short
  EXPECT_FALSE(decode_end(bytes("{\"result\": \"won\", \"reason\": \"x\"}")));      // no such result
  EXPECT_FALSE(decode_end(bytes("{\"result\": 1, \"reason\": \"x\"}")));            // not a name
  EXPECT_FALSE(decode_end(bytes("{\"reason\": \"x\"}")));                           // no result
  EXPECT_FALSE(decode_end(bytes("[\"failed\", \"x\"]")));                           // not an object
  EXPECT_FALSE(decode_end(bytes("{\"result\": \"failed\", \"reason\": \"" + std::string(70000, 'x') + "\"}")));  // past its bound
  const std::optional<PeerEnd> ok = decode_end(bytes("{\"result\": \"failed\", \"reason\": \"x\"}"));
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->result, RunResult::failed);
}
