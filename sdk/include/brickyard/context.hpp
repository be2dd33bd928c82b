#pragma once
// What a running node sees of the framework: time, parameters, typed ports, logs, metrics.
// Plugins never read the wall clock: now() is the run's clock (sim or real).
#include <brickyard/abi.hpp>
#include <brickyard/message_traits.hpp>
#include <brickyard/params.hpp>

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard {

// A sample of an input of any type (Manifest::input_any): the message as CDR, as on the wire,
// its encapsulation header first. (ABI 2.3)
struct SerializedSample {
  std::vector<unsigned char> cdr;
};

namespace detail {
// Type-erased port endpoints implemented by the host.
struct InputChannel {
  virtual ~InputChannel() = default;
  virtual const std::string& type_name() const = 0;
  virtual std::vector<std::shared_ptr<const void>> take() = 0;   // new samples, oldest first
  virtual std::shared_ptr<const void> latest() const = 0;        // last sample ever received
  virtual bool connected() const = 0;
  // ABI 2.3, appended: for an input of any type, the type its wire carries ("" when unwired) and
  // that type's IDL text (null when unwired).
  virtual const std::string& wire_type() const { return type_name(); }
  virtual const char* wire_idl() const { return nullptr; }
};
struct OutputChannel {
  virtual ~OutputChannel() = default;
  virtual const std::string& type_name() const = 0;
  virtual void publish(std::shared_ptr<const void> sample) = 0;
  // ABI 2.3, appended: for an output of any type, the type of the inputs it feeds ("" when it
  // feeds none) and that type's IDL text (null then).
  virtual const std::string& wire_type() const { return type_name(); }
  virtual const char* wire_idl() const { return nullptr; }
};
}  // namespace detail

template <class T> class Input {
 public:
  Input() = default;
  explicit Input(detail::InputChannel* c) : ch_(c) {}
  // Samples that arrived since the last take(), oldest first.
  std::vector<std::shared_ptr<const T>> take() {
    std::vector<std::shared_ptr<const T>> out;
    if (!ch_) return out;
    for (auto& s : ch_->take()) out.push_back(std::static_pointer_cast<const T>(std::move(s)));
    return out;
  }
  // The most recent sample (null before the first one).
  std::shared_ptr<const T> latest() const {
    return ch_ ? std::static_pointer_cast<const T>(ch_->latest()) : nullptr;
  }
  bool connected() const { return ch_ && ch_->connected(); }

 private:
  detail::InputChannel* ch_ = nullptr;
};

template <class T> class Output {
 public:
  Output() = default;
  explicit Output(detail::OutputChannel* c) : ch_(c) {}
  void publish(T msg) { publish(std::make_shared<const T>(std::move(msg))); }
  // Readers in the same process get this very object: do not modify it after publishing.
  void publish(std::shared_ptr<const T> msg) {
    if (ch_) ch_->publish(std::static_pointer_cast<const void>(std::move(msg)));
  }

 private:
  detail::OutputChannel* ch_ = nullptr;
};

// An input of any type: its samples as CDR, with the wire's type name and IDL to decode them by.
class AnyInput {
 public:
  AnyInput() = default;
  explicit AnyInput(detail::InputChannel* c) : ch_(c) {}
  // "brickyard::msgs::Path"; empty when the input is not wired.
  const std::string& type_name() const {
    static const std::string none;
    return ch_ ? ch_->wire_type() : none;
  }
  // The IDL text that defines the type (and the types it uses); null when not wired.
  const char* idl() const { return ch_ ? ch_->wire_idl() : nullptr; }
  std::vector<std::shared_ptr<const SerializedSample>> take() {
    std::vector<std::shared_ptr<const SerializedSample>> out;
    if (!ch_) return out;
    for (auto& s : ch_->take()) out.push_back(std::static_pointer_cast<const SerializedSample>(std::move(s)));
    return out;
  }
  bool connected() const { return ch_ && ch_->connected(); }

 private:
  detail::InputChannel* ch_ = nullptr;
};

// An output of any type: samples published as CDR of the type its readers take.
class AnyOutput {
 public:
  AnyOutput() = default;
  explicit AnyOutput(detail::OutputChannel* c) : ch_(c) {}
  // The type of the inputs it feeds; empty when it feeds none.
  const std::string& type_name() const {
    static const std::string none;
    return ch_ ? ch_->wire_type() : none;
  }
  const char* idl() const { return ch_ ? ch_->wire_idl() : nullptr; }
  // The host decodes it for the readers; bytes that are not a sample of the type fail the run.
  void publish(SerializedSample sample) {
    if (ch_) ch_->publish(std::make_shared<const SerializedSample>(std::move(sample)));
  }

 private:
  detail::OutputChannel* ch_ = nullptr;
};

enum class LogLevel { debug, info, warn, error };

// Throw from configure() when a parameter, or a file a parameter names, is wrong: the host stops
// before any node runs and exits with code 2 (bad input), printing the node and this message.
// Name the culprit in the message: the file and line, the parameter, the offending value.
class BRICKYARD_EXPORT BadInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Trigger {
  // readable: the descriptor the node waits on (Context::wake_on_readable) has something to read.
  enum class Kind { periodic, input, readable };
  Kind kind = Kind::periodic;
  std::string port;  // for input triggers
};

class Context {
 public:
  virtual ~Context() = default;

  virtual std::int64_t now_ns() const = 0;
  double now_s() const { return static_cast<double>(now_ns()) * 1e-9; }
  virtual bool sim_clock() const = 0;
  virtual const std::string& node_name() const = 0;
  virtual const Params& params() const = 0;
  // Seed for this node's random sources: derived from the run's --seed and the node name.
  virtual std::uint64_t seed() const = 0;
  virtual const Trigger& trigger() const = 0;

  virtual void log(LogLevel level, std::string_view message) = 0;
  // Metrics end up in summary.json under nodes.<node>.metrics.<name>.
  virtual void metric(std::string_view name, double value) = 0;
  virtual void metric(std::string_view name, std::vector<double> values) = 0;
  virtual void metric(std::string_view name, std::string value) = 0;

  // The graph's own end condition: stop the run, successfully.
  virtual void finish(std::string_view reason) = 0;
  // The run failed (an assertion, a crash of the car): stop, exit code 1.
  virtual void fail(std::string_view reason) = 0;

  // A file named in a parameter. Absolute paths are taken as they are; a relative one is looked
  // for next to the graph file, in the working directory, then in the data folders
  // ($BRICKYARD_DATA_PATH, then <prefix>/share/brickyard/data). Throws BadInput naming every
  // place it looked when none has it.
  virtual std::string find_file(std::string_view path) const = 0;

  template <class T> Input<T> input(std::string_view port) {
    auto* c = input_channel(port);
    check_type(c->type_name(), message_traits<T>::name, port);
    return Input<T>(c);
  }
  // An input declared with Manifest::input_any.
  AnyInput input_any(std::string_view port) {
    auto* c = input_channel(port);
    check_type(c->type_name(), kAnyMessageType, port);
    return AnyInput(c);
  }
  // An output declared with Manifest::output_any.
  AnyOutput output_any(std::string_view port) {
    auto* c = output_channel(port);
    if (!is_any_message_type(c->type_name())) check_type(c->type_name(), kAnyMessageType, port);
    return AnyOutput(c);
  }
  template <class T> Output<T> output(std::string_view port) {
    auto* c = output_channel(port);
    check_type(c->type_name(), message_traits<T>::name, port);
    return Output<T>(c);
  }

 protected:
  // Throw std::invalid_argument when the manifest declares no such port.
  virtual detail::InputChannel* input_channel(std::string_view port) = 0;
  virtual detail::OutputChannel* output_channel(std::string_view port) = 0;

 public:
  // A live status field for the run's progress line ("speed", "40.2 m/s"; "mode", "PATH"):
  // `brickyard run` shows the newest of each while it runs. Not kept in the summary (use metric).
  // Appended last so that plugins built against ABI 1.1 keep their vtable (ABI 1.2).
  virtual void status(std::string_view field, std::string_view value) = 0;
  // A driver's device: on the real clock the node also steps as soon as `fd` has something to
  // read (or has failed: a step then finds the error), not only on its period, so what arrives
  // waits for no poll. One descriptor per node; -1 stops the waking (a device that failed would
  // otherwise wake it without end). The node keeps owning the descriptor. On the sim clock a node
  // steps on its period and inputs alone: this is ignored. Call it from configure or a step (ABI 3.1).
  virtual void wake_on_readable(int fd) = 0;

 private:
  static void check_type(const std::string& declared, const char* requested, std::string_view port) {
    if (declared != requested)
      throw std::logic_error("port '" + std::string(port) + "' carries " + declared + ", not " + requested);
  }
};

}  // namespace brickyard
