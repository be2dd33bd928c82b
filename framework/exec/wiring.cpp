// Executive::build: this process's nodes with their ports — a DDS writer per output, a tap per
// output that is recorded or served live (--live) — then the wires: same-process inputs by pointer, inputs whose writer
// runs in another process through a DDS reader.
#include "exec/crash_guard.hpp"
#include "exec/executive.hpp"
#include "exec/lockstep.hpp"
#include "exec/node_runtime.hpp"
#include "exec/seeding.hpp"
#include "record/recorder.hpp"
#include "record/sample_serializer.hpp"
#include "transport/shm_reclaim.hpp"
#include "record/recorded_scene.hpp"

#include <algorithm>
#include <map>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <set>
#include <tuple>
#include <utility>

namespace brickyard::fw {

namespace {

DdsSettings dds_settings(const ResolvedGraph& graph, const RunOptions& opt) {
  const GraphDecl& g = *graph.decl;
  DdsSettings ds;
  ds.domain = opt.domain.value_or(g.transport.domain);
  ds.interfaces = g.transport.interfaces;
  ds.peers = g.transport.peers;
  ds.shared_memory = g.transport.shared_memory;
  ds.ros2_naming = g.transport.ros2_naming;
  ds.security = opt.security;
  ds.lockstep = graph.lockstep;
  ds.name = participant_name(opt.process.empty() ? "all" : opt.process);
  return ds;
}

// Another process's node in a lockstep run: its ports, so that this process queues the same
// turns; no plugin, writer or tap (its process has them).
std::unique_ptr<NodeRuntime> make_phantom(const ResolvedNode& rn) {
  auto n = std::make_unique<NodeRuntime>();
  n->rn = &rn;
  n->name = rn.decl->name;
  n->phantom = true;
  for (const auto& p : rn.plugin->manifest.ports) {
    if (p.direction == PortDirection::input) {
      n->inputs.push_back(std::make_unique<InputQueue>(p.name, p.type_name, p.depth, true, true));
    } else {
      n->outputs.push_back(std::make_unique<OutputPort>(p.name, p.type_name));
      n->outputs.back()->index = static_cast<std::uint16_t>(n->outputs.size() - 1);
    }
  }
  return n;
}

// An input of any type takes its writer's type: each sample serialized for it.
void serialize_for_any_input(InputQueue& in, const std::string& wire_type) {
  auto serializer = std::make_shared<std::pair<SampleSerializer, std::mutex>>(std::piecewise_construct, std::forward_as_tuple(wire_type),
                                                                              std::forward_as_tuple());
  const char* idl = idl_text(wire_type);
  in.take_any(wire_type, idl ? omgidl_schema(idl) : std::string(), [serializer](const void* m) -> std::shared_ptr<const void> {
    std::lock_guard<std::mutex> l(serializer->second);
    const auto b = serializer->first.serialize(m);
    auto s = std::make_shared<SerializedSample>();
    s->cdr.assign(b.data, b.data + b.size);
    return s;
  });
}

}  // namespace

void Executive::build() {
  make_transport();
  NodesByName by_name;
  for (const auto& rn : graph_.nodes) {
    if (!rn.here) {
      auto n = make_phantom(rn);
      by_name.phantom[n->name] = n.get();
      sched_.push_back(n.get());
      phantoms_.push_back(std::move(n));
      continue;
    }
    NodeRuntime* n = add_node(rn);
    by_name.here[n->name] = n;
  }
  if (graph_.lockstep) make_lockstep();
  // A split run on the real clock: each process says how its run ended (exec/peer_ends.hpp).
  // Keys made before end records existed do not permit their topics: the run goes on without.
  if (!sim() && !opt_.process.empty() && graph_.processes.size() > 1) {
    try {
      ends_ = std::make_unique<PeerEnds>(*transport_, opt_.process, graph_.processes,
                                         [this](const std::string& p, const PeerEnd& e) { peer_ended(p, e); });
    } catch (const std::runtime_error& e) {
      console_.line([&] {
        std::fprintf(stderr, "[brickyard] warning: the processes cannot say how their runs ended (%s): `brickyard security init` again permits it\n",
                     e.what());
      });
    }
  }
  for (const auto& w : graph_.decl->wires) wire(w, by_name);
}

void Executive::make_transport() {
  DdsSettings ds = dds_settings(graph_, opt_);
  if (ds.shared_memory) {  // what killed processes left in /dev/shm, before this one adds its own
    const ReclaimedSegments r = reclaim_dead_segments();
    if (!r.files.empty() && !opt_.quiet)
      std::fprintf(stderr, "notice: removed %zu shared-memory segment%s (%.1f MB) that processes which died had left in /dev/shm\n",
                   r.files.size(), r.files.size() == 1 ? "" : "s", static_cast<double>(r.bytes) / 1e6);
  }
  crash_guard::snapshot_shared_memory();
  transport_ = std::make_unique<DdsTransport>(ds);
  crash_guard::note_shared_memory();  // the participant's own segment and port files, made just now
  if (live_) scene_ = std::make_unique<LiveScene>(*live_);
  if (recorder_ && opt_.record_scene.value_or(opt_.record_only.empty())) {
    scene_recording_ = std::make_unique<RecordedScene>(*recorder_);
    recorded_scene_ = std::make_unique<LiveScene>(*scene_recording_);
  }
}

NodeRuntime* Executive::add_node(const ResolvedNode& rn) {
  auto n = std::make_unique<NodeRuntime>();
  n->rn = &rn;
  n->name = rn.decl->name;
  n->seed = node_seed(opt_.seed, n->name);
  std::set<std::string> wired;
  for (const auto& w : graph_.decl->wires)
    if (w.to.node == n->name) wired.insert(w.to.port);
  for (const auto& p : rn.plugin->manifest.ports) {
    if (p.direction == PortDirection::input) {
      n->inputs.push_back(std::make_unique<InputQueue>(p.name, p.type_name, p.depth, wired.count(p.name) > 0));
      n->inputs.back()->clock = [this] { return now_ns(); };
    } else {
      add_output(*n, p);
    }
  }
  n->ctx = std::make_unique<NodeContext>(*this, *n);
  console_.add_node(n->name);
  sched_.push_back(n.get());
  nodes_.push_back(std::move(n));
  return nodes_.back().get();
}

void Executive::add_output(NodeRuntime& n, const PortSpec& p) {
  const std::string topic = n.name + "." + p.name;
  n.outputs.push_back(std::make_unique<OutputPort>(p.name, p.type_name));
  OutputPort& out = *n.outputs.back();
  out.index = static_cast<std::uint16_t>(n.outputs.size() - 1);
  // An output of any type sends its readers' type: the plugin's CDR decoded for them here.
  std::string type = p.type_name;
  if (is_any_message_type(type)) {
    const auto t = graph_.output_types.find(topic);
    type = t == graph_.output_types.end() ? std::string() : t->second;
    const char* idl = type.empty() ? nullptr : idl_text(type);
    out.make_any(type, idl ? omgidl_schema(idl) : std::string());
  }
  if (!type.empty()) {  // (an output of any type that feeds nothing has no writer, nothing to record)
    out.writer = transport_->make_writer(topic_name(n.name, p.name), type);
    tap_output(out, topic, type);
  }
}

void Executive::make_lockstep() {
  std::vector<std::string> owner;
  for (const auto& rn : graph_.nodes) owner.push_back(rn.decl->process);
  lock_ = std::make_unique<Lockstep>(*transport_, opt_.process, std::move(owner), lockstep_fingerprint(graph_, opt_.seed, sim_end_ns()));
  for (auto& n : nodes_)
    for (auto& o : n->outputs)
      o->write_failed = [this, node = n->name](const std::string& port) {
        request_stop(RunResult::failed, "lockstep: a sample of " + node + "." + port + " could not be sent to another process within 10 s");
      };
}

void Executive::wire(const WireDecl& w, const NodesByName& by_name) {
  auto to = by_name.here.find(w.to.node);
  if (to == by_name.here.end()) {
    // Its reader lives in another process; in a lockstep run its phantom here is queued too.
    if (auto p = by_name.phantom.find(w.to.node); p != by_name.phantom.end()) {
      NodeRuntime* from = by_name.here.count(w.from.node) ? by_name.here.at(w.from.node) : by_name.phantom.at(w.from.node);
      from->output(w.from.port)->local.push_back(p->second->input(w.to.port));
    }
    return;
  }
  InputQueue* in = to->second->input(w.to.port);
  // The writer's type: what an input of any type takes (its samples serialized for it).
  const std::string& wire_type = graph_.wire_types.at(w.to.text());
  if (in->type_name() == kAnyMessageType) serialize_for_any_input(*in, wire_type);
  auto from = by_name.here.find(w.from.node);
  if (from != by_name.here.end()) {
    from->second->output(w.from.port)->local.push_back(in);
  } else {
    // Lockstep: the phantom's publishes replayed push this input, in wire order, each with the
    // next sample its reader took (Lockstep::feed).
    OutputPort* by_phantom = lock_ ? by_name.phantom.at(w.from.node)->output(w.from.port) : nullptr;
    if (by_phantom) by_phantom->local.push_back(in);
    connect_remote_input(w, *to->second, in, wire_type, by_phantom);
  }
}

// A writer in another process that dies is noticed within the liveliness lease (0.5 s), said at
// once, and the run fails at its end naming the input and its writer (unless its process may
// die); one that comes back (restarted) is said too.
void Executive::connect_remote_input(const WireDecl& w, const NodeRuntime& to, InputQueue* in, const std::string& wire_type,
                                     OutputPort* by_phantom) {
  const PortSpec* ps = to.rn->plugin->manifest.port(w.to.port);
  auto ri = std::make_unique<RemoteInput>();
  ri->input = w.to.text();
  ri->writer = w.from.text();
  ri->process = graph_.decl->nodes.at(w.from.node).process;
  RemoteInput* r = ri.get();
  remote_inputs_.push_back(std::move(ri));
  // Only the writer the graph names feeds the input: a sample from any other participant (a
  // second writer on the topic: a forged command) is dropped and said, unless the graph
  // accepts them (transport.foreign_writers). Without DDS security this tells a stray or
  // naive writer, not one that lies about its name (docs/security.md).
  WriterCheck check;
  check.expected = participant_name(r->process);
  check.accept_others = graph_.decl->transport.accept_foreign_writers;
  check.other = [this, r](const std::string& participant, const std::string& writer) { foreign_writer(*r, participant, writer); };
  r->reader = transport_->make_reader(
      topic_name(w.from.node, w.from.port), wire_type, ps->depth,
      by_phantom ? lock_->feed(&lock_wires_[{by_phantom, in}], r->process)
                 : std::function<void(std::shared_ptr<const void>)>([in, r](std::shared_ptr<const void> s) {
                     r->last_sample_ns = std::chrono::duration_cast<std::chrono::nanoseconds>(
                                             std::chrono::steady_clock::now().time_since_epoch()).count();
                     in->push(std::move(s));
                   }),
      [this, r](bool alive) { peer_liveliness(*r, alive); }, std::move(check));
}

}  // namespace brickyard::fw
