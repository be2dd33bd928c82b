#pragma once
// A split run on the real clock: each process says how its run ended (its result and reason) on
// brickyard_end/PROCESS just before it leaves, and hears the others' while it runs
// (docs/reliability.md). A peer that leaves cleanly does not lapse its writers' liveliness, so
// without it a healthy process whose peer failed (a node threw, a check failed) ended "success";
// one whose plugin called exit() leaves cleanly too (Fast DDS tears its participant down in
// exit's handlers) and never says its end: that is told by its end writer leaving unsaid.
#include "exec/run_types.hpp"
#include "transport/dds.hpp"

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace brickyard::fw {

struct PeerEnd {
  RunResult result = RunResult::success;
  std::string reason;
};

// The record on the wire: JSON text, {"result": "failed", "reason": "..."}. Null for bytes that
// are not one (a damaged or foreign record).
std::vector<std::uint8_t> encode_end(const PeerEnd& end);
std::optional<PeerEnd> decode_end(const std::vector<std::uint8_t>& bytes);

class PeerEnds {
 public:
  // `heard`: on a DDS thread, once per peer, with the end it said (a damaged record: failed,
  // saying so).
  using Heard = std::function<void(const std::string& process, const PeerEnd& end)>;
  PeerEnds(DdsTransport& t, const std::string& me, const std::set<std::string>& processes, Heard heard);

  // The peers met during the run that have left without saying how their run ended. A peer's
  // record may trail its leaving: one that left unsaid is waited for, at most `grace_s`.
  std::vector<std::string> left_unsaid(double grace_s);
  // Says this process's end, and waits at most `seconds` for the peers that hear it to take it.
  void say(const PeerEnd& end, double seconds);

 private:
  struct Peer {
    DdsReader* reader = nullptr;
    std::atomic<bool> met{false}, said{false};
  };
  DdsWriter* writer_;
  std::map<std::string, std::unique_ptr<Peer>> peers_;
  std::string me_;
};

}  // namespace brickyard::fw
