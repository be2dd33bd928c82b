// testing.stack_cut: what a vehicle interface hears of the stack, passed on until `cut_s` of the
// run, then nothing: the stack's process killed, seen from an interface that outlives it, on the
// sim clock in one process (where a process cannot die and rejoin; docs/vehicle-interface.md,
// "The stop along the last path"). The commands, the path and the estimate, each as it came.
#include <brickyard/msgs/ControlCommand.h>
#include <brickyard/msgs/LocalizationEstimate.h>
#include <brickyard/msgs/Path.h>
#include <brickyard/plugin.hpp>

namespace {

using namespace brickyard;

struct Settings {
  double cut_s = 1e9;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("cut_s", &Settings::cut_s).in_unit("s").range(0, 1e9).doc("from this time of the run on, nothing is passed on");
  return b;
}

struct Ports {
  Input<msgs::ControlCommand> command_in;
  Input<msgs::Path> path_in;
  Input<msgs::LocalizationEstimate> estimate_in;
  Output<msgs::ControlCommand> command;
  Output<msgs::Path> path;
  Output<msgs::LocalizationEstimate> estimate;
};

PortBinding<Ports> ports() {
  PortBinding<Ports> b;
  b.input("command_in", &Ports::command_in).doc("the stack's commands").steps().depth(16);
  b.input("path_in", &Ports::path_in).doc("its path").optional().steps().depth(4);
  b.input("estimate_in", &Ports::estimate_in).doc("its estimate").optional().steps().depth(16);
  b.output("command", &Ports::command).doc("the commands, until cut_s");
  b.output("path", &Ports::path).doc("the path, until cut_s");
  b.output("estimate", &Ports::estimate).doc("the estimate, until cut_s");
  return b;
}

class StackCut : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest("testing.stack_cut", "1.0.0")
        .describe("the stack's commands, path and estimate passed on until cut_s, then nothing (a killed stack, on the sim clock)")
        .with_ports(ports())
        .parameters(bindings());
  }

  void configure(Context& ctx) override {
    cut_ns_ = static_cast<std::int64_t>(bindings().read(ctx.params()).cut_s * 1e9);
    io_ = ports().connect(ctx);
  }

  void step(Context& ctx) override {
    const bool cut = ctx.now_ns() >= cut_ns_;
    pass(io_.command_in, io_.command, cut);
    pass(io_.path_in, io_.path, cut);
    pass(io_.estimate_in, io_.estimate, cut);
  }

  void deactivate(Context& ctx) override { ctx.metric("passed", static_cast<double>(passed_)); }

 private:
  template <class In, class Out> void pass(In& in, Out& out, bool cut) {
    for (const auto& m : in.take()) {
      if (cut) continue;
      out.publish(*m);
      ++passed_;
    }
  }

  std::int64_t cut_ns_ = 0;
  std::uint64_t passed_ = 0;
  Ports io_;
};

}  // namespace

BRICKYARD_PLUGINS(StackCut)
