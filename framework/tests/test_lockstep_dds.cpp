// Lockstep's waits between processes (exec/lockstep.hpp) with two participants in one process
// over DDS (run in a private network namespace on a domain of its own: tests/CMakeLists.txt):
// peers that end hear each other's ends and verdicts, and a peer whose end never comes holds the
// other no longer than the wait's limit, and is named.
#include "exec/lockstep.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <future>
#include <optional>
#include <string>

using namespace brickyard::fw;

namespace {

DdsSettings settings(const std::string& process) {
  DdsSettings s;
  const char* domain = std::getenv("BRICKYARD_TEST_DOMAIN");
  s.domain = domain ? std::atoi(domain) : 0;
  s.name = participant_name(process);
  s.lockstep = true;
  return s;
}

// One process of a run split into "a" and "b".
struct Process {
  DdsTransport transport;
  Lockstep lock;
  explicit Process(const std::string& me) : transport(settings(me)), lock(transport, me, {"a", "b"}, 42) {}

  bool start() {
    std::string why;
    std::optional<std::pair<RunResult, std::string>> peer_stop;
    return lock.start(20, [] { return true; }, LockRecord{}, why, peer_stop);
  }
};

bool start_both(Process& a, Process& b) {
  std::future<bool> b_started = std::async(std::launch::async, [&] { return b.start(); });
  const bool a_started = a.start();
  return b_started.get() && a_started;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST(LockstepDds, PeersThatEndHearEachOthersEndsAndVerdicts) {
  Process a("a"), b("b");
  ASSERT_TRUE(start_both(a, b));
  LockRecord verdict;
  verdict.node = 1;
  verdict.result = static_cast<std::uint8_t>(RunResult::failed);
  verdict.reason = "node 'referee': did not finish";
  std::future<std::string> b_ended = std::async(std::launch::async, [&] {
    std::string why;
    b.lock.finish(RunResult::success, "sim clock reached the end", {}, {verdict}, why, 30);
    return why;
  });
  std::string why;
  const std::vector<LockRecord> theirs = a.lock.finish(RunResult::success, "sim clock reached the end", {}, {}, why, 30);
  EXPECT_EQ(why, "");
  EXPECT_EQ(b_ended.get(), "");
  ASSERT_EQ(theirs.size(), 1u);
  EXPECT_EQ(theirs[0].reason, verdict.reason);
  EXPECT_EQ(theirs[0].result, verdict.result);
}

TEST(LockstepDds, APeerWhoseEndNeverComesIsNamedOnceTheWaitIsOver) {
  Process a("a"), b("b");
  ASSERT_TRUE(start_both(a, b));
  // b stays alive and matched and never ends: before the limit, a waited for it for ever.
  const auto t0 = std::chrono::steady_clock::now();
  std::string why;
  const std::vector<LockRecord> theirs = a.lock.finish(RunResult::success, "sim clock reached the end", {}, {}, why, 1.0);
  const double took = seconds_since(t0);
  EXPECT_TRUE(theirs.empty());
  EXPECT_EQ(why, "lockstep: process 'b' did not end its run within 1 s of this one's end (its end record never came)");
  EXPECT_GE(took, 1.0);
  EXPECT_LT(took, 10.0);  // the limit, then at most 5 s for a's records to be acknowledged
}
