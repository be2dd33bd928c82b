// Lockstep: the records of a split run on the sim clock, their clock topics, and the waits
// (lockstep.hpp says why).
#include "exec/lockstep.hpp"

#include <brickyard/msgs/Blob.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>

namespace brickyard::fw {

namespace {

constexpr const char* kBlob = "brickyard::msgs::Blob";
constexpr std::uint8_t kVersion = 1;
constexpr std::size_t kMaxBatch = 4096;  // records queued before they are sent without waiting

void put(std::vector<std::uint8_t>& b, std::uint64_t v) {
  while (v >= 0x80) {
    b.push_back(static_cast<std::uint8_t>(v | 0x80));
    v >>= 7;
  }
  b.push_back(static_cast<std::uint8_t>(v));
}

struct Reader {
  const std::vector<std::uint8_t>& b;
  std::size_t at = 0;
  std::uint8_t byte() {
    if (at >= b.size()) throw std::runtime_error("a clock record cut short at byte " + std::to_string(at));
    return b[at++];
  }
  std::uint64_t var() {
    std::uint64_t v = 0;
    for (int shift = 0; shift < 64; shift += 7) {
      const std::uint8_t c = byte();
      v |= static_cast<std::uint64_t>(c & 0x7f) << shift;
      if (!(c & 0x80)) return v;
    }
    throw std::runtime_error("a clock record's number runs past 64 bits at byte " + std::to_string(at));
  }
};

std::uint64_t zigzag(std::int64_t v) { return (static_cast<std::uint64_t>(v) << 1) ^ static_cast<std::uint64_t>(v >> 63); }
std::int64_t unzigzag(std::uint64_t v) { return static_cast<std::int64_t>(v >> 1) ^ -static_cast<std::int64_t>(v & 1); }

struct Fnv {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) h = (h ^ static_cast<const std::uint8_t*>(p)[i]) * 1099511628211ull;
  }
  void add(const std::string& s) {
    add(s.data(), s.size());
    add("\0", 1);
  }
  void add(std::int64_t v) { add(&v, sizeof v); }
};

}  // namespace

std::vector<std::uint8_t> encode_records(const std::vector<LockRecord>& rs) {
  std::vector<std::uint8_t> b{kVersion};
  for (const auto& r : rs) {
    b.push_back(r.kind);
    put(b, r.seq);
    put(b, r.node);
    put(b, zigzag(r.t_ns));
    put(b, r.pubs.size());
    for (auto p : r.pubs) put(b, p);
    b.push_back(r.stop ? 1 : 0);
    if (r.stop) {
      b.push_back(r.result);
      put(b, r.reason.size());
      b.insert(b.end(), r.reason.begin(), r.reason.end());
    }
    if (r.kind == LockRecord::hello)
      for (int i = 0; i < 8; ++i) b.push_back(static_cast<std::uint8_t>(r.fingerprint >> (8 * i)));
  }
  return b;
}

std::vector<LockRecord> decode_records(const std::vector<std::uint8_t>& bytes) {
  Reader in{bytes};
  if (in.byte() != kVersion) throw std::runtime_error("a clock record of another version");
  std::vector<LockRecord> out;
  while (in.at < bytes.size()) {
    LockRecord r;
    const std::uint8_t k = in.byte();
    if (k < LockRecord::hello || k > LockRecord::deactivated) throw std::runtime_error("a clock record of unknown kind " + std::to_string(k));
    r.kind = static_cast<LockRecord::Kind>(k);
    r.seq = in.var();
    r.node = static_cast<std::uint32_t>(in.var());
    r.t_ns = unzigzag(in.var());
    const std::uint64_t n = in.var();
    if (n > bytes.size()) throw std::runtime_error("a clock record with more publishes than bytes");
    for (std::uint64_t i = 0; i < n; ++i) r.pubs.push_back(static_cast<std::uint16_t>(in.var()));
    r.stop = in.byte() != 0;
    if (r.stop) {
      r.result = in.byte();
      const std::uint64_t len = in.var();
      if (len > bytes.size() - in.at) throw std::runtime_error("a clock record's reason runs past its end");
      r.reason.assign(bytes.begin() + static_cast<long>(in.at), bytes.begin() + static_cast<long>(in.at + len));
      in.at += len;
    }
    if (r.kind == LockRecord::hello)
      for (int i = 0; i < 8; ++i) r.fingerprint |= static_cast<std::uint64_t>(in.byte()) << (8 * i);
    out.push_back(std::move(r));
  }
  return out;
}

std::uint64_t lockstep_fingerprint(const ResolvedGraph& g, std::uint64_t seed, std::int64_t end_ns) {
  Fnv f;
  f.add(static_cast<std::int64_t>(seed));
  f.add(end_ns);
  f.add(static_cast<std::int64_t>(std::llround(g.decl->clock.step_s * 1e9)));
  for (const auto& n : g.nodes) {
    f.add(n.decl->name);
    f.add(n.plugin->manifest.name);
    f.add(n.decl->process);
    f.add(n.period_ns);
    f.add(n.latency_ns);
    for (const auto& t : n.trigger_inputs) f.add(t);
    f.add(n.decl->params.dump());
  }
  for (const auto& w : g.decl->wires) {
    f.add(w.from.text());
    f.add(w.to.text());
  }
  return f.h;
}

Lockstep::Lockstep(DdsTransport& t, std::string me, std::vector<std::string> owner, std::uint64_t fingerprint)
    : me_(std::move(me)), owner_(std::move(owner)), fingerprint_(fingerprint) {
  clock_ = t.make_writer(clock_topic(me_), kBlob);
  for (const auto& p : owner_) {
    if (p == me_ || peers_.count(p)) continue;
    Peer& peer = peers_[p];
    WriterCheck check;
    check.expected = participant_name(p);
    peer.reader = t.make_reader(
        clock_topic(p), kBlob, 64,
        [this, p](std::shared_ptr<const void> s) {
          const auto& blob = *static_cast<const msgs::Blob*>(s.get());
          std::vector<LockRecord> rs;
          std::string damage;
          try {
            rs = decode_records(blob.data());
          } catch (const std::exception& e) {
            damage = e.what();
          }
          std::lock_guard<std::mutex> l(m_);
          Peer& q = peers_.at(p);
          q.heard = std::chrono::steady_clock::now();
          if (!damage.empty()) {
            LockRecord end;
            end.kind = LockRecord::end;
            end.stop = true;
            end.result = static_cast<std::uint8_t>(RunResult::failed);
            end.reason = "lockstep: process '" + p + "' sent a damaged clock record (" + damage + ")";
            q.end = end;
          }
          for (auto& r : rs) {
            if (r.kind == LockRecord::hello) q.hello = r;
            else if (r.kind == LockRecord::end) q.end = r;
            else if (r.kind == LockRecord::deactivated) q.deactivated.push_back(std::move(r));
            else q.in.push_back(std::move(r));
          }
          cv_.notify_all();
        },
        [this, p](bool alive) {
          if (alive) return;
          std::lock_guard<std::mutex> l(m_);
          Peer& q = peers_.at(p);
          q.lost = true;
          if (q.heard != std::chrono::steady_clock::time_point{})
            q.silent_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - q.heard).count();
          cv_.notify_all();
        },
        std::move(check));
  }
}

Lockstep::~Lockstep() = default;

std::function<void(std::shared_ptr<const void>)> Lockstep::feed(const void* key, const std::string& process) {
  {
    std::lock_guard<std::mutex> l(m_);
    wires_[key].process = process;
  }
  return [this, key](std::shared_ptr<const void> s) {
    std::lock_guard<std::mutex> l(m_);
    wires_.at(key).samples.push_back(std::move(s));
    cv_.notify_all();
  };
}

std::string Lockstep::gone(const std::string& process, std::optional<std::pair<RunResult, std::string>>* peer_stop) {
  if (g_interrupt) return "interrupted";
  const Peer& p = peers_.at(process);
  // (An end ends a wait for records, which come before it on the same topic; not one for a
  // sample, which comes on another and may be later: it was acknowledged before its process left.)
  if (p.end && peer_stop) {
    if (peer_stop) *peer_stop = {static_cast<RunResult>(p.end->result), p.end->reason};
    return "lockstep: process '" + process + "' ended its run (" + p.end->reason + ") before this one's event " + std::to_string(seq_);
  }
  if (p.lost) {
    char heard[64] = "nothing ever heard from it";
    if (p.heard != std::chrono::steady_clock::time_point{}) std::snprintf(heard, sizeof heard, "nothing from it for %.2f s", p.silent_s);
    return "lockstep: process '" + process + "' went silent (" + heard +
           ", its clock's liveliness lapsed: did it die?); a run on the sim clock cannot go on without it";
  }
  if (p.hello && p.reader->matched() == 0) return "lockstep: process '" + process + "' left the run without ending it";
  return {};
}

std::shared_ptr<const void> Lockstep::sample(const void* key, std::string& why) {
  std::unique_lock<std::mutex> l(m_);
  Wire& w = wires_.at(key);
  while (w.samples.empty()) {
    why = gone(w.process, nullptr);  // lost or left
    if (!why.empty()) return nullptr;
    cv_.wait_for(l, std::chrono::milliseconds(50));
  }
  auto s = std::move(w.samples.front());
  w.samples.pop_front();
  return s;
}

bool Lockstep::start(double timeout_s, const std::function<bool()>& matched, const LockRecord& my_hello, std::string& why,
                     std::optional<std::pair<RunResult, std::string>>& peer_stop) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                            std::chrono::duration<double>(timeout_s));
  auto late = [&](const std::string& what) {
    char secs[32];
    std::snprintf(secs, sizeof secs, "%.3g s", timeout_s);
    why = "start-up: " + what + " within " + secs + " (transport.startup_timeout_s; did it start?)";
    return false;
  };
  // Everything matched: a sample written before its reader is known would be lost.
  for (;;) {
    bool all = matched() && clock_->matched() >= static_cast<int>(peers_.size());
    std::string missing;
    for (auto& [name, p] : peers_)
      if (p.reader->matched() == 0 && missing.empty()) missing = name;
    if (all && missing.empty()) break;
    if (g_interrupt) return why = "interrupted", false;
    if (std::chrono::steady_clock::now() > until)
      return late(missing.empty() ? "the lockstep's writers and readers were not all matched"
                                  : "process '" + missing + "' did not join the lockstep");
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  LockRecord h = my_hello;
  h.kind = LockRecord::hello;
  h.fingerprint = fingerprint_;
  outbox_.push_back(h);
  flush();
  std::unique_lock<std::mutex> l(m_);
  for (auto& [name, p] : peers_) {
    while (!p.hello) {
      if (g_interrupt) return why = "interrupted", false;
      if (p.lost || std::chrono::steady_clock::now() > until) {
        l.unlock();
        return late("process '" + name + "' did not say it is ready");
      }
      cv_.wait_for(l, std::chrono::milliseconds(50));
    }
    if (p.hello->fingerprint != fingerprint_) {
      why = "lockstep: process '" + name + "' runs the graph with other settings (--seed, --set, --arg or --duration): a split run on the sim clock needs the same";
      return false;
    }
    if (p.hello->stop) {
      peer_stop = std::make_pair(static_cast<RunResult>(p.hello->result), p.hello->reason);
      why = p.hello->reason;
      return false;
    }
  }
  return true;
}

void Lockstep::done(LockRecord r) {
  r.kind = LockRecord::event;
  r.seq = seq_++;
  outbox_.push_back(std::move(r));
  if (outbox_.size() >= kMaxBatch) flush();
}

bool Lockstep::await(std::uint32_t node, std::int64_t t_ns, LockRecord& out, std::string& why,
                     std::optional<std::pair<RunResult, std::string>>& peer_stop) {
  flush();  // what this process did is sent before it waits: the owner of this event may need it
  const std::string& p = owner_.at(node);
  std::unique_lock<std::mutex> l(m_);
  Peer& peer = peers_.at(p);
  while (peer.in.empty()) {
    why = gone(p, &peer_stop);
    if (!why.empty()) return false;
    cv_.wait_for(l, std::chrono::milliseconds(50));
  }
  out = std::move(peer.in.front());
  peer.in.pop_front();
  if (out.seq != seq_ || out.node != node || out.t_ns != t_ns) {
    char msg[256];
    std::snprintf(msg, sizeof msg, "lockstep: the processes diverged at event %llu: process '%s' sent event %llu (node %u at t = %.9f s), this one expected node %u at t = %.9f s",
                  static_cast<unsigned long long>(seq_), p.c_str(), static_cast<unsigned long long>(out.seq), out.node,
                  static_cast<double>(out.t_ns) * 1e-9, node, static_cast<double>(t_ns) * 1e-9);
    why = msg;
    return false;
  }
  ++seq_;
  return true;
}

void Lockstep::flush() {
  if (outbox_.empty()) return;
  msgs::Blob b;
  b.header().frame_id(me_);
  b.header().seq(static_cast<std::uint32_t>(seq_));
  b.data() = encode_records(outbox_);
  outbox_.clear();
  clock_->write(&b);
}

std::vector<LockRecord> Lockstep::finish(RunResult r, const std::string& reason, const std::vector<DdsWriter*>& writers,
                                        const std::vector<LockRecord>& mine, std::string& why, double end_wait_s) {
  for (LockRecord d : mine) {
    d.kind = LockRecord::deactivated;
    d.stop = true;
    outbox_.push_back(std::move(d));
  }
  LockRecord e;
  e.kind = LockRecord::end;
  e.seq = seq_;
  e.stop = true;
  e.result = static_cast<std::uint8_t>(r);
  e.reason = reason;
  outbox_.push_back(std::move(e));
  flush();
  // Every peer's end: its verdicts come before it. A peer behind this one is still stepping, to
  // its end: until its death, its leaving, an interrupt or end_wait_s (transport.end_timeout_s:
  // graph.hpp says why it is enough).
  std::vector<LockRecord> theirs;
  {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                              std::chrono::duration<double>(end_wait_s));
    std::unique_lock<std::mutex> l(m_);
    for (auto& [name, p] : peers_) {
      if (!p.hello) continue;  // it never joined (start-up failed): no end will come
      while (!p.end) {
        std::string g = gone(name, nullptr);
        if (g.empty() && std::chrono::steady_clock::now() > until) {
          char secs[32];
          std::snprintf(secs, sizeof secs, "%.3g s", end_wait_s);
          g = "lockstep: process '" + name + "' did not end its run within " + secs + " of this one's end (its end record never came)";
        }
        if (!g.empty()) {
          if (why.empty()) why = g;
          break;
        }
        cv_.wait_for(l, std::chrono::milliseconds(50));
      }
      if (p.end) theirs.insert(theirs.end(), p.deactivated.begin(), p.deactivated.end());
    }
  }
  // The peers may be behind: what they will replay must reach them before this process goes.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  auto left = [&] { return std::max(0.0, std::chrono::duration<double>(until - std::chrono::steady_clock::now()).count()); };
  clock_->wait_acked(left());
  for (DdsWriter* w : writers)
    if (w->matched() > 0) w->wait_acked(left());
  return theirs;
}

}  // namespace brickyard::fw
