#include "exec/node_context.hpp"
#include "exec/node_runtime.hpp"

#include <sys/eventfd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace brickyard::fw {

std::int64_t NodeContext::now_ns() const { return t_step_now_ns >= 0 ? t_step_now_ns : e_.now_ns(); }
bool NodeContext::sim_clock() const { return e_.sim(); }
const std::string& NodeContext::node_name() const { return n_.name; }
const Params& NodeContext::params() const { return n_.rn->params; }
std::uint64_t NodeContext::seed() const { return n_.seed; }
const Trigger& NodeContext::trigger() const { return n_.trigger; }
void NodeContext::log(LogLevel level, std::string_view message) { e_.log(n_, level, message); }
void NodeContext::metric(std::string_view name, double value) {
  n_.metrics[std::string(name)] = std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}
void NodeContext::metric(std::string_view name, std::vector<double> values) {
  n_.metrics[std::string(name)] = values;
}
void NodeContext::metric(std::string_view name, std::string value) { n_.metrics[std::string(name)] = value; }
void NodeContext::finish(std::string_view reason) {
  e_.request_stop(RunResult::success, "node '" + n_.name + "' finished the run: " + std::string(reason));
}
std::string NodeContext::find_file(std::string_view path) const { return e_.find_file(path); }
void NodeContext::status(std::string_view field, std::string_view value) { e_.set_status(n_.name, field, value); }
void NodeContext::fail(std::string_view reason) {
  e_.request_stop(RunResult::failed, "node '" + n_.name + "' (" + n_.plugin_name() + "): " + std::string(reason));
}

void NodeContext::wake_on_readable(int fd) {
  if (e_.sim()) return;  // the sim clock steps on periods and inputs alone: its runs stay the same bit for bit
  std::lock_guard<std::mutex> l(n_.m);
  if (fd >= 0 && n_.wake_event_fd < 0) {
    n_.wake_event_fd = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (n_.wake_event_fd < 0) throw std::runtime_error("node '" + n_.name + "': wake_on_readable: eventfd: " + std::strerror(errno));
  }
  n_.device_fd = fd < 0 ? -1 : fd;
  n_.wake_device_wait();  // a thread already waiting picks the new descriptor up
}

detail::InputChannel* NodeContext::input_channel(std::string_view port) {
  if (auto* i = n_.input(port)) return i;
  throw std::invalid_argument("plugin " + n_.plugin_name() + " has no input port '" + std::string(port) + "'");
}
detail::OutputChannel* NodeContext::output_channel(std::string_view port) {
  if (auto* o = n_.output(port)) return o;
  throw std::invalid_argument("plugin " + n_.plugin_name() + " has no output port '" + std::string(port) + "'");
}

}  // namespace brickyard::fw
