#pragma once
// One sim clock across processes (docs/reliability.md, "One sim clock across processes").
//
// Every process of a split graph on the sim clock runs the whole graph's schedule: its own nodes
// for real, the others' as phantoms (ports, no plugin). So every process makes the same decisions
// in the same order — which node steps next, which turns a sample queues — and each step or
// latency delivery (an event) is numbered alike everywhere. The process that owns an event does
// it and appends a record to its clock topic (`brickyard_clock/PROCESS`): its number, node, time,
// the outputs it published on in order, and the stop it asked for. Every other process, when its
// replica reaches that event, waits for the record and replays it: each publish pushes its
// readers' queues in the wire order — a phantom's only queues its turn, a real input takes the
// next sample of that wire from DDS, where the owner wrote it. So each process's queues get the
// same samples in the same order at the same sim time as in one process: the run is the same,
// bit for bit.
//
// Records are sent in batches: before the process waits for another's event, at the end of each
// instant, and at the end. Every event's owner has the records of the events before it once it
// gets there, so no two processes wait on each other. A peer whose clock topic's liveliness
// lapses (it died) or that ended its run is said, and the run stops.
#include "exec/run_types.hpp"
#include "graph/resolve.hpp"
#include "transport/dds.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace brickyard::fw {

struct LockRecord {
  enum Kind : std::uint8_t { hello = 1, event = 2, end = 3, deactivated = 4 };
  Kind kind = event;
  std::uint64_t seq = 0;              // event: its number in the run; end: the events done
  std::uint32_t node = 0;             // event, deactivated: the node's place in the schedule
  std::int64_t t_ns = 0;              // event: its sim time
  std::vector<std::uint16_t> pubs;    // event: the outputs published on, in order
  bool stop = false;                  // event: it ended the run; hello: this process could not start; end,
                                      // deactivated (what its deactivate asked for): always
  std::uint8_t result = 0;            // RunResult of the stop
  std::string reason;
  std::uint64_t fingerprint = 0;      // hello: the graph and settings this process runs
};

// Records in a clock topic's bytes (little-endian varints); throws std::runtime_error on damage.
std::vector<std::uint8_t> encode_records(const std::vector<LockRecord>& rs);
std::vector<LockRecord> decode_records(const std::vector<std::uint8_t>& bytes);

// The graph as a run sees it, hashed: two processes with other --set, --arg, --seed or
// --duration would not replay each other's events.
std::uint64_t lockstep_fingerprint(const ResolvedGraph& g, std::uint64_t seed, std::int64_t end_ns);

class Lockstep {
 public:
  // `owner`: each schedule place's process.
  Lockstep(DdsTransport& t, std::string me, std::vector<std::string> owner, std::uint64_t fingerprint);
  ~Lockstep();

  const std::string& owner(std::size_t node) const { return owner_.at(node); }
  bool mine(std::size_t node) const { return owner_.at(node) == me_; }

  // The DDS delivery of a real input fed by another process's output (key: that wire): its
  // samples wait here until the event that published them is replayed.
  std::function<void(std::shared_ptr<const void>)> feed(const void* key, const std::string& process);
  // That wire's next sample, waiting for it; null (and `why`) if its process is lost or ended.
  std::shared_ptr<const void> sample(const void* key, std::string& why);

  // Start-up, once this process's nodes are activated (or failed to): every writer and reader
  // matched (`matched()` says), then a hello to and from every peer. False with `why` when a
  // peer does not come within `timeout_s`, runs another graph, or could not start (`peer_stop`
  // then holds its result and reason).
  bool start(double timeout_s, const std::function<bool()>& matched, const LockRecord& my_hello, std::string& why,
             std::optional<std::pair<RunResult, std::string>>& peer_stop);

  // This process did event `seq()` (its record is queued).
  void done(LockRecord r);
  // Another process's event `seq()`: its record, waited for. False with `why` (and maybe a
  // stop the peer ended with) when it cannot come.
  bool await(std::uint32_t node, std::int64_t t_ns, LockRecord& out, std::string& why,
             std::optional<std::pair<RunResult, std::string>>& peer_stop);
  std::uint64_t seq() const { return seq_; }

  void flush();
  // The run is over here and this process's nodes deactivated: what their deactivate asked for
  // (`mine`: a sink's verdict), then an end record, sent; every peer's awaited (those still
  // stepping, to their end) and returned; everything written acknowledged by the peers (at most
  // 5 s) before the transport goes. A lost peer is left out (`why` says so), and so is one whose
  // end has not come `end_wait_s` after this process's own (`why` names it).
  std::vector<LockRecord> finish(RunResult r, const std::string& reason, const std::vector<DdsWriter*>& writers,
                                 const std::vector<LockRecord>& mine, std::string& why, double end_wait_s);

 private:
  struct Peer {
    DdsReader* reader = nullptr;
    std::deque<LockRecord> in;
    std::optional<LockRecord> hello, end;
    std::vector<LockRecord> deactivated;
    bool lost = false;
    // Its last record's arrival, and how long before its liveliness was found lapsed: the
    // silence this process itself saw, whatever the machine's load did to its log's readers.
    std::chrono::steady_clock::time_point heard{};
    double silent_s = 0;
  };
  struct Wire {
    std::string process;
    std::deque<std::shared_ptr<const void>> samples;
  };
  // Under m_: why a wait on `process` cannot end (lost, left, interrupted; ended, where
  // `peer_stop` is given: a wait for its records), else empty.
  std::string gone(const std::string& process, std::optional<std::pair<RunResult, std::string>>* peer_stop);

  std::string me_;
  std::vector<std::string> owner_;
  std::uint64_t fingerprint_;
  DdsWriter* clock_ = nullptr;
  std::mutex m_;
  std::condition_variable cv_;
  std::map<std::string, Peer> peers_;
  std::map<const void*, Wire> wires_;
  std::vector<LockRecord> outbox_;
  std::uint64_t seq_ = 0;
};

}  // namespace brickyard::fw
