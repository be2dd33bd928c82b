#pragma once
// The Context a node's plugin is handed: its name, parameters, seed, trigger and ports, and the
// run's clock, logs, metrics, status fields, file search and end requests, served by its host
// (the Executive).
#include "exec/run_types.hpp"

#include <brickyard/context.hpp>

#include <cstdint>
#include <string>
#include <string_view>

namespace brickyard::fw {

class NodeRuntime;

// What a node's context asks of the run that hosts it.
class NodeHost {
 public:
  virtual std::int64_t now_ns() const = 0;
  virtual bool sim() const = 0;
  virtual std::string find_file(std::string_view path) const = 0;
  virtual void log(const NodeRuntime& n, LogLevel level, std::string_view msg) = 0;
  virtual void request_stop(RunResult r, std::string reason) = 0;
  virtual void set_status(const std::string& node, std::string_view field, std::string_view value) = 0;

 protected:
  ~NodeHost() = default;
};

class NodeContext final : public Context {
 public:
  NodeContext(NodeHost& e, NodeRuntime& n) : e_(e), n_(n) {}
  std::int64_t now_ns() const override;
  bool sim_clock() const override;
  const std::string& node_name() const override;
  const Params& params() const override;
  std::uint64_t seed() const override;
  const Trigger& trigger() const override;
  void log(LogLevel level, std::string_view message) override;
  void metric(std::string_view name, double value) override;
  void metric(std::string_view name, std::vector<double> values) override;
  void metric(std::string_view name, std::string value) override;
  void finish(std::string_view reason) override;
  std::string find_file(std::string_view path) const override;
  void status(std::string_view field, std::string_view value) override;
  void fail(std::string_view reason) override;
  void wake_on_readable(int fd) override;

 protected:
  detail::InputChannel* input_channel(std::string_view port) override;
  detail::OutputChannel* output_channel(std::string_view port) override;

 private:
  NodeHost& e_;
  NodeRuntime& n_;
};

}  // namespace brickyard::fw
