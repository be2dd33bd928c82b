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
// that its last frame feeds runs, and the run is still the same on any number of threads.
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

void Executive::run_sim() {
  const std::int64_t end_ns = sim_end_ns();
  // Every node stepped here in schedule order; in a lockstep run the other processes' phantoms
  // among them, whose turns are their owners' records replayed (remote_event).
  const std::vector<NodeRuntime*>& nodes = sched_;

  using Due = std::pair<std::int64_t, std::size_t>;  // (time, schedule order): earliest, then upstream first
  std::priority_queue<Due, std::vector<Due>, std::greater<Due>> timers;
  std::deque<std::size_t> ready;  // input-triggered steps queued at this instant, in publish order
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    NodeRuntime& n = *nodes[i];
    if (n.rn->period_ns > 0) timers.push({0, i});
    for (auto& in : n.inputs) {
      if (!n.rn->trigger_inputs.count(in->name())) continue;
      in->on_arrival = [&n, &ready, i](const std::string& port) {
        if (n.queued) return;
        n.queued = true;
        n.queued_port = port;
        ready.push_back(i);
      };
    }
  }
  const std::vector<NodeSet> reach = reach_within_instant(nodes);
  AheadPool pool(thread_count(opt_.threads) - 1, [this](NodeRuntime& n) {
    t_deferred = &n.deferred;
    t_step_now_ns = n.ahead_now_ns;
    n.ahead_ok = step_body(n, n.ahead_trigger);
    t_step_now_ns = -1;
    t_deferred = nullptr;
  });
  std::vector<std::size_t> due;  // the periodic steps of this instant, in schedule order
  std::size_t next_due = 0;      // the first not yet taken
  NodeSet before(nodes.size());
  const Trigger periodic{Trigger::Kind::periodic, {}};
  // The instant's queue is `ready`, then due[next_due..]: its head steps now; each later step
  // that nothing before it can change is handed out.
  auto hand_out = [&] {
    if (ready.size() + (due.size() - next_due) < 2) return;
    before.clear();
    bool head = true;
    auto consider = [&](std::size_t i, bool timer) {
      NodeRuntime& n = *nodes[i];
      if (!head && !before.has(i) && !n.phantom && n.ahead.load() == 0 && !n.undelivered) {
        n.ahead_trigger = timer ? periodic : Trigger{Trigger::Kind::input, n.queued_port};
        n.ahead_now_ns = sim_now_ns_;
        pool.hand_out(n);
      }
      head = false;
      before.add(i);
      before.add(reach[i]);
    };
    for (std::size_t i : ready) consider(i, false);
    for (std::size_t k = next_due; k < due.size(); ++k) consider(due[k], true);
  };
  // Latency steps whose outputs wait: (time, order taken) -> the node and, once it is done
  // (collected), what it did.
  struct Delivery {
    std::size_t node;
    bool collected = false, ok = false;
    Deferred effects;
  };
  std::map<std::pair<std::int64_t, std::uint64_t>, Delivery> deliveries;
  std::uint64_t taken = 0;
  // A latency step is done: its held inputs arrive, what it did is kept for its delivery.
  auto collect = [&](Delivery& d) {
    NodeRuntime& n = *nodes[d.node];
    d.collected = true;
    if (n.phantom) return;  // its owner steps it
    if (n.ahead.load() != 0) {
      pool.wait(n);
      n.ahead.store(0);
    }
    for (auto& in : n.inputs) in->release();
    d.effects.swap(n.deferred);
    d.ok = n.ahead_ok;
    n.undelivered = false;
  };
  auto collect_node = [&](std::size_t i) {
    for (auto& [at, d] : deliveries)
      if (d.node == i && !d.collected) collect(d);
  };
  // A latency step's turn: handed out (with no helper, this thread steps it when it is
  // collected: the same step, on the inputs held for it) and its delivery set.
  auto latency_turn = [&](std::size_t i) {
    NodeRuntime& n = *nodes[i];
    if (n.phantom) {  // its delivery is its owner's event
      deliveries[{sim_now_ns_ + n.rn->latency_ns, taken++}].node = i;
      return;
    }
    if (n.undelivered) collect_node(i);  // a latency of one whole period: the last step first
    if (n.ahead.load() == 0) {
      n.ahead_trigger = periodic;
      n.ahead_now_ns = sim_now_ns_;
      pool.hand_out(n);
    }
    n.undelivered = true;
    for (auto& in : n.inputs) in->hold();
    deliveries[{sim_now_ns_ + n.rn->latency_ns, taken++}].node = i;
  };
  // After an instant's steps: the latency steps due now deliver, in the order they stepped.
  auto deliver = [&] {
    bool any = false;
    while (!stop_ && !deliveries.empty() && deliveries.begin()->first.first == sim_now_ns_) {
      Delivery d = std::move(deliveries.begin()->second);
      deliveries.erase(deliveries.begin());
      any = true;
      if (nodes[d.node]->phantom) {
        remote_event(d.node, sim_now_ns_);
        continue;
      }
      local_event(d.node, sim_now_ns_, [&] {
        if (!d.collected) collect(d);
        for (auto& f : d.effects) f();
        if (d.ok) ++nodes[d.node]->steps;
      });
    }
    return any;
  };
  // The run is over: every latency step still out finishes (as with one thread, where it has
  // stepped), and what it did is dropped.
  auto drop_deliveries = [&] {
    for (auto& [at, d] : deliveries)
      if (!d.collected) collect(d);
    deliveries.clear();
  };
  // A step's turn: stepped now, or, when it was handed out, what it did then is done now.
  auto turn = [&](std::size_t i, Trigger t) {
    NodeRuntime& n = *nodes[i];
    if (n.rn->latency_ns > 0) {
      latency_turn(i);
      return;
    }
    if (n.phantom) {
      remote_event(i, sim_now_ns_);
      return;
    }
    if (n.ahead.load() == 0) {
      local_event(i, sim_now_ns_, [&] { step(n, std::move(t)); });
      return;
    }
    pool.wait(n);
    n.ahead.store(0);
    Deferred d;
    d.swap(n.deferred);
    if (stop_) return;  // the run ended before its turn: it never stepped, as far as the run knows
    local_event(i, sim_now_ns_, [&] {
      for (auto& f : d) f();
      if (n.ahead_ok) ++n.steps;
    });
  };
  // The run ends inside an instant: the steps handed out finish, and what they did is dropped.
  auto settle = [&] {
    auto drop = [&](std::size_t i) {
      NodeRuntime& n = *nodes[i];
      if (n.ahead.load() == 0 || n.undelivered) return;  // a latency step: drop_deliveries
      pool.wait(n);
      n.ahead.store(0);
      n.deferred.clear();
    };
    for (std::size_t i : ready) drop(i);
    for (std::size_t k = next_due; k < due.size(); ++k) drop(due[k]);
  };

  std::uint64_t events = 0;
  while (!stop_) {
    if (timers.empty() && deliveries.empty()) {
      host_log("no periodic node left to step: the run ends");
      break;
    }
    std::int64_t t = timers.empty() ? INT64_MAX : timers.top().first;
    if (!deliveries.empty()) t = std::min(t, deliveries.begin()->first.first);
    if (t > end_ns) {
      sim_now_ns_ = end_ns;
      break;
    }
    sim_now_ns_ = t;
    if (live_) live_->time(static_cast<std::uint64_t>(t));
    if (opt_.pace > 0) pace(t);
    due.clear();
    next_due = 0;
    while (!timers.empty() && timers.top().first == t) {
      due.push_back(timers.top().second);
      timers.pop();
    }
    while (!stop_) {
      if (ready.empty() && next_due == due.size() && !deliver()) break;
      if (ready.empty() && next_due == due.size()) continue;
      hand_out();
      if (!ready.empty()) {
        const std::size_t i = ready.front();
        ready.pop_front();
        nodes[i]->queued = false;
        turn(i, Trigger{Trigger::Kind::input, nodes[i]->queued_port});
        continue;
      }
      if (g_interrupt) {
        request_stop(RunResult::interrupted, "interrupted");
        break;
      }
      const std::size_t i = due[next_due++];
      turn(i, periodic);
      timers.push({t + nodes[i]->rn->period_ns, i});
      if ((++events & 255) == 0) progress();
    }
    if (lock_) lock_->flush();  // the instant's records: a peer behind this process catches up
    if (stop_) settle();
  }
  drop_deliveries();
}

}  // namespace brickyard::fw
