// Executive::run_sim: the sim clock. Discrete events: at each instant the due periodic nodes step
// in schedule order (upstream first), and a published sample steps its input-triggered
// subscribers at the same instant, in publish order, before the next timer. That order is the
// run: nothing here reads the wall clock, so a graph and a seed make the same run, bit for bit.
//
// Steps that cannot see each other run side by side (docs/performance.md). Before each turn, the
// steps queued later in the instant that nothing queued before them can change — no sample of an
// earlier step, nor of the steps that sample triggers in turn, reaches them — are handed out to
// helper threads. A step run ahead sees exactly the inputs it would have seen at its turn, and
// what it does (publish, log, fail) is kept and done at its turn, in order. So the run is the
// same bit for bit on any number of threads; the one thing threads cannot undo: when a step ends
// the run, the steps already handed out at that instant have stepped (their effects dropped), on
// one thread as on four, so that too is the same.
//
// A node with a modelled latency (Manifest::delivered_after: a LiDAR whose frame is ready once
// its sweep is over) steps at its instant, reading the inputs of that instant, but what it does
// is done `latency` later, after that instant's own steps. Its step may run on a helper beside
// everything until then: samples published to it meanwhile wait (InputQueue::hold) until it is
// done, and it sees the time of its instant. So a LiDAR's next frame is cast while the chain
// that its last frame feeds runs, and the run is still the same on any number of threads. A node
// woken by its inputs may have a latency too (a localizer's computing time): a sample that comes
// while its step is out waits, and wakes it once the step is done (collected: at its delivery,
// or at the run's end), at that instant, reading all that waited.
#include "exec/ahead_pool.hpp"
#include "exec/executive.hpp"
#include "exec/lockstep.hpp"
#include "exec/node_runtime.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <queue>
#include <thread>

namespace brickyard::fw {

namespace {

// Sets of nodes (by schedule position) as bits.
struct NodeSet {
  std::vector<std::uint64_t> w;
  explicit NodeSet(std::size_t n = 0) : w((n + 63) / 64, 0) {}
  bool has(std::size_t i) const { return (w[i >> 6] >> (i & 63)) & 1; }
  void add(std::size_t i) { w[i >> 6] |= std::uint64_t{1} << (i & 63); }
  void add(const NodeSet& o) {
    for (std::size_t k = 0; k < w.size(); ++k) w[k] |= o.w[k];
  }
  void clear() { std::fill(w.begin(), w.end(), 0); }
};

// Per node: the nodes whose inputs a step of it can change within the same instant — those its
// outputs reach, and, for each of those its sample triggers, theirs in turn.
std::vector<NodeSet> reach_within_instant(const std::vector<NodeRuntime*>& nodes) {
  const std::size_t n = nodes.size();
  std::map<const InputQueue*, std::size_t> owner;
  for (std::size_t i = 0; i < n; ++i)
    for (auto& in : nodes[i]->inputs) owner[in.get()] = i;
  std::vector<NodeSet> direct(n, NodeSet(n)), triggers(n, NodeSet(n));
  for (std::size_t i = 0; i < n; ++i)
    for (auto& out : nodes[i]->outputs)
      if (nodes[i]->rn->latency_ns == 0)  // a latency step's samples arrive at a later instant
        for (const InputQueue* q : out->local) {
          const std::size_t j = owner.at(q);
          direct[i].add(j);
          if (nodes[j]->rn->trigger_inputs.count(q->name())) triggers[i].add(j);
        }
  std::vector<NodeSet> reach(n, NodeSet(n));
  for (std::size_t i = 0; i < n; ++i) {
    NodeSet seen(n);
    std::vector<std::size_t> stack{i};
    seen.add(i);
    while (!stack.empty()) {
      const std::size_t a = stack.back();
      stack.pop_back();
      reach[i].add(direct[a]);
      for (std::size_t j = 0; j < n; ++j)
        if (triggers[a].has(j) && !seen.has(j)) {
          seen.add(j);
          stack.push_back(j);
        }
    }
  }
  return reach;
}

int thread_count(int asked) {
  if (asked > 0) return asked;
  const unsigned hw = std::thread::hardware_concurrency();
  return static_cast<int>(std::clamp(hw, 1u, 4u));
}

}  // namespace

// Another process's event: its record awaited and replayed — each publish pushes the phantom's
// readers in wire order, a real one with the next sample its DDS reader took.
void Executive::remote_event(std::size_t i, std::int64_t t_ns) {
  LockRecord r;
  std::string why;
  std::optional<std::pair<RunResult, std::string>> peer_stop;
  if (!lock_->await(static_cast<std::uint32_t>(i), t_ns, r, why, peer_stop)) {
    lockstep_failed(why, peer_stop);
    return;
  }
  NodeRuntime& n = *sched_[i];
  for (const std::uint16_t p : r.pubs) {
    if (p >= n.outputs.size()) {
      lockstep_failed("lockstep: process '" + lock_->owner(i) + "' sent a publish on output " + std::to_string(p) + " of node '" +
                          n.name + "', which has " + std::to_string(n.outputs.size()),
                      {});
      return;
    }
    OutputPort& o = *n.outputs[p];
    for (InputQueue* q : o.local) {
      if (q->phantom()) {
        q->push(nullptr);
        continue;
      }
      auto s = lock_->sample(&lock_wires_.at({&o, q}), why);
      if (!s) {
        lockstep_failed(why, {});
        return;
      }
      q->push(std::move(s));
    }
  }
  if (r.stop) request_stop(static_cast<RunResult>(r.result), r.reason);
}

void Executive::record_local_event(std::size_t i, std::int64_t t_ns, std::vector<std::uint16_t> pubs, bool stopped_before) {
  LockRecord r;
  r.node = static_cast<std::uint32_t>(i);
  r.t_ns = t_ns;
  r.pubs = std::move(pubs);
  if (!stopped_before && stop_) {
    std::lock_guard<std::mutex> l(stop_m_);
    r.stop = true;
    r.result = static_cast<std::uint8_t>(stop_result_.value_or(RunResult::failed));
    r.reason = stop_reason_;
  }
  lock_->done(std::move(r));
}

void Executive::lockstep_failed(const std::string& why, const std::optional<std::pair<RunResult, std::string>>& peer_stop) {
  // Said at once, even with --quiet: the run ends here, and its verdict comes after deactivation.
  if (why != "interrupted" && !peer_stop) console_.line([&] { std::fprintf(stderr, "[brickyard] %s\n", why.c_str()); });
  if (peer_stop) request_stop(peer_stop->first, peer_stop->second);
  else if (why == "interrupted") request_stop(RunResult::interrupted, why);
  else request_stop(RunResult::failed, why);
}

std::int64_t Executive::sim_end_ns() const {
  const auto dur = opt_.duration_s ? opt_.duration_s : graph_.decl->clock.duration_s;
  return dur ? static_cast<std::int64_t>(std::llround(*dur * 1e9)) : INT64_MAX;
}

// One run of the sim clock: the timers, the instant's queue, the latency steps whose outputs
// wait, and the helpers that step ahead.
class Executive::SimRun {
 public:
  explicit SimRun(Executive& e);
  void run();

 private:
  // A latency step whose outputs wait: the node and, once it is done (collected), what it did.
  struct Delivery {
    std::size_t node;
    bool collected = false, ok = false;
    Deferred effects;
  };
  using Due = std::pair<std::int64_t, std::size_t>;  // (time, schedule order): earliest, then upstream first

  void arm();                          // the periodic nodes' first timers, the input triggers' wake-ups
  void begin_instant(std::int64_t t);  // the clock at t, the periodic steps due then taken
  void step_instant(std::int64_t t);   // the instant's steps and deliveries, until none is left
  void hand_out();
  void consider(std::size_t i, bool timer, bool& head);
  void collect(Delivery& d);
  void collect_node(std::size_t i);
  void latency_turn(std::size_t i, const Trigger& t);
  bool deliver();
  void drop_deliveries();
  void turn(std::size_t i, Trigger t);
  void settle();

  Executive& e_;
  const std::int64_t end_ns_;
  // Every node stepped here in schedule order; in a lockstep run the other processes' phantoms
  // among them, whose turns are their owners' records replayed (remote_event).
  const std::vector<NodeRuntime*>& nodes_;
  std::priority_queue<Due, std::vector<Due>, std::greater<Due>> timers_;
  std::deque<std::size_t> ready_;  // input-triggered steps queued at this instant, in publish order
  std::vector<NodeSet> reach_;
  std::optional<AheadPool> pool_;  // made once the nodes are armed
  std::vector<std::size_t> due_;   // the periodic steps of this instant, in schedule order
  std::size_t next_due_ = 0;       // the first not yet taken
  NodeSet before_;
  const Trigger periodic_{Trigger::Kind::periodic, {}};
  // Latency steps whose outputs wait, by (time, order taken).
  std::map<std::pair<std::int64_t, std::uint64_t>, Delivery> deliveries_;
  std::uint64_t taken_ = 0;
  std::uint64_t events_ = 0;
};

Executive::SimRun::SimRun(Executive& e) : e_(e), end_ns_(e.sim_end_ns()), nodes_(e.sched_), before_(e.sched_.size()) {
  arm();
  reach_ = reach_within_instant(nodes_);
  pool_.emplace(thread_count(e_.opt_.threads) - 1, [&e = e_](NodeRuntime& n) {
    t_deferred = &n.deferred;
    t_step_now_ns = n.ahead_now_ns;
    n.ahead_ok = e.step_body(n, n.ahead_trigger);
    t_step_now_ns = -1;
    t_deferred = nullptr;
  });
}

void Executive::SimRun::arm() {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    NodeRuntime& n = *nodes_[i];
    if (n.rn->period_ns > 0) timers_.push({0, i});
    for (auto& in : n.inputs) {
      if (!n.rn->trigger_inputs.count(in->name())) continue;
      in->on_arrival = [&n, &ready = ready_, i](const std::string& port) {
        if (n.queued) return;
        n.queued = true;
        n.queued_port = port;
        ready.push_back(i);
      };
    }
  }
}

void Executive::SimRun::run() {
  while (!e_.stop_) {
    if (timers_.empty() && deliveries_.empty()) {
      e_.host_log("no periodic node left to step: the run ends");
      break;
    }
    std::int64_t t = timers_.empty() ? INT64_MAX : timers_.top().first;
    if (!deliveries_.empty()) t = std::min(t, deliveries_.begin()->first.first);
    if (t > end_ns_) {
      e_.sim_now_ns_ = end_ns_;
      break;
    }
    begin_instant(t);
    step_instant(t);
    if (e_.lock_) e_.lock_->flush();  // the instant's records: a peer behind this process catches up
    if (e_.stop_) settle();
  }
  drop_deliveries();
}

void Executive::SimRun::begin_instant(std::int64_t t) {
  e_.sim_now_ns_ = t;
  if (e_.live_) e_.live_->time(static_cast<std::uint64_t>(t));
  if (e_.opt_.pace > 0) e_.pace(t);
  due_.clear();
  next_due_ = 0;
  while (!timers_.empty() && timers_.top().first == t) {
    due_.push_back(timers_.top().second);
    timers_.pop();
  }
}

void Executive::SimRun::step_instant(std::int64_t t) {
  while (!e_.stop_) {
    if (ready_.empty() && next_due_ == due_.size() && !deliver()) break;
    if (ready_.empty() && next_due_ == due_.size()) continue;
    hand_out();
    if (!ready_.empty()) {
      const std::size_t i = ready_.front();
      ready_.pop_front();
      nodes_[i]->queued = false;
      turn(i, Trigger{Trigger::Kind::input, nodes_[i]->queued_port});
      continue;
    }
    if (g_interrupt) {
      e_.request_stop(RunResult::interrupted, interrupt_reason());
      break;
    }
    const std::size_t i = due_[next_due_++];
    turn(i, periodic_);
    timers_.push({t + nodes_[i]->rn->period_ns, i});
    if ((++events_ & 255) == 0) e_.progress();
  }
}

// The instant's queue is `ready_`, then due_[next_due_..]: its head steps now; each later step
// that nothing before it can change is handed out.
void Executive::SimRun::hand_out() {
  if (ready_.size() + (due_.size() - next_due_) < 2) return;
  before_.clear();
  bool head = true;
  for (std::size_t i : ready_) consider(i, false, head);
  for (std::size_t k = next_due_; k < due_.size(); ++k) consider(due_[k], true, head);
}

// The queue's next step: handed out unless it is the head, or a step before it can change it.
void Executive::SimRun::consider(std::size_t i, bool timer, bool& head) {
  NodeRuntime& n = *nodes_[i];
  if (!head && !before_.has(i) && !n.phantom && n.ahead.load() == 0 && !n.undelivered) {
    n.ahead_trigger = timer ? periodic_ : Trigger{Trigger::Kind::input, n.queued_port};
    n.ahead_now_ns = e_.sim_now_ns_;
    pool_->hand_out(n);
  }
  head = false;
  before_.add(i);
  before_.add(reach_[i]);
}

// A latency step is done: its held inputs arrive, what it did is kept for its delivery.
void Executive::SimRun::collect(Delivery& d) {
  NodeRuntime& n = *nodes_[d.node];
  d.collected = true;
  if (n.phantom) return;  // its owner steps it
  if (n.ahead.load() != 0) {
    pool_->wait(n);
    n.ahead.store(0);
  }
  for (auto& in : n.inputs) in->release();
  d.effects.swap(n.deferred);
  d.ok = n.ahead_ok;
  n.undelivered = false;
}

void Executive::SimRun::collect_node(std::size_t i) {
  for (auto& [at, d] : deliveries_)
    if (d.node == i && !d.collected) collect(d);
}

// A latency step's turn: handed out (with no helper, this thread steps it when it is
// collected: the same step, on the inputs held for it) and its delivery set.
void Executive::SimRun::latency_turn(std::size_t i, const Trigger& t) {
  NodeRuntime& n = *nodes_[i];
  if (n.phantom) {  // its delivery is its owner's event
    deliveries_[{e_.sim_now_ns_ + n.rn->latency_ns, taken_++}].node = i;
    return;
  }
  if (n.undelivered) collect_node(i);  // a latency of one whole period: the last step first
  if (n.ahead.load() == 0) {
    n.ahead_trigger = t;
    n.ahead_now_ns = e_.sim_now_ns_;
    pool_->hand_out(n);
  }
  n.undelivered = true;
  for (auto& in : n.inputs) in->hold();
  deliveries_[{e_.sim_now_ns_ + n.rn->latency_ns, taken_++}].node = i;
}

// After an instant's steps: the latency steps due now deliver, in the order they stepped.
bool Executive::SimRun::deliver() {
  bool any = false;
  while (!e_.stop_ && !deliveries_.empty() && deliveries_.begin()->first.first == e_.sim_now_ns_) {
    Delivery d = std::move(deliveries_.begin()->second);
    deliveries_.erase(deliveries_.begin());
    any = true;
    if (nodes_[d.node]->phantom) {
      e_.remote_event(d.node, e_.sim_now_ns_);
      continue;
    }
    e_.local_event(d.node, e_.sim_now_ns_, [&] {
      if (!d.collected) collect(d);
      for (auto& f : d.effects) f();
      if (d.ok) ++nodes_[d.node]->steps;
    });
  }
  return any;
}

// The run is over: every latency step still out finishes (as with one thread, where it has
// stepped), and what it did is dropped.
void Executive::SimRun::drop_deliveries() {
  for (auto& [at, d] : deliveries_)
    if (!d.collected) collect(d);
  deliveries_.clear();
}

// A step's turn: stepped now, or, when it was handed out, what it did then is done now.
void Executive::SimRun::turn(std::size_t i, Trigger t) {
  NodeRuntime& n = *nodes_[i];
  if (n.rn->latency_ns > 0) {
    latency_turn(i, t);
    return;
  }
  if (n.phantom) {
    e_.remote_event(i, e_.sim_now_ns_);
    return;
  }
  if (n.ahead.load() == 0) {
    e_.local_event(i, e_.sim_now_ns_, [&] { e_.step(n, std::move(t)); });
    return;
  }
  pool_->wait(n);
  n.ahead.store(0);
  Deferred d;
  d.swap(n.deferred);
  if (e_.stop_) return;  // the run ended before its turn: it never stepped, as far as the run knows
  e_.local_event(i, e_.sim_now_ns_, [&] {
    for (auto& f : d) f();
    if (n.ahead_ok) ++n.steps;
  });
}

// The run ends inside an instant: the steps handed out finish, and what they did is dropped.
void Executive::SimRun::settle() {
  auto drop = [&](std::size_t i) {
    NodeRuntime& n = *nodes_[i];
    if (n.ahead.load() == 0 || n.undelivered) return;  // a latency step: drop_deliveries
    pool_->wait(n);
    n.ahead.store(0);
    n.deferred.clear();
  };
  for (std::size_t i : ready_) drop(i);
  for (std::size_t k = next_due_; k < due_.size(); ++k) drop(due_[k]);
}

void Executive::run_sim() {
  SimRun sim(*this);
  sim.run();
}

}  // namespace brickyard::fw
