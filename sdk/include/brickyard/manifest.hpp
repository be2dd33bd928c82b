#pragma once
// What a plugin declares about itself: ports, parameters, triggers. The host validates a
// graph against manifests before it constructs any plugin.
#include <brickyard/message_traits.hpp>
#include <brickyard/params.hpp>

#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard {

template <class S> class ParamBinding;
template <class P> class PortBinding;

enum class PortDirection { input, output };

struct PortSpec {
  std::string name;
  PortDirection direction = PortDirection::input;
  std::string type_name;   // "brickyard::msgs::GnssFix"
  std::string type_hash;   // message_traits<T>::hash at the plugin's build
  std::string description;
  bool required = true;    // inputs: must be wired
  std::uint32_t depth = 16;  // inputs: samples kept before the oldest is dropped
};

struct ParamSpec {
  std::string name;
  ParamType type = ParamType::number;
  std::optional<ParamValue> default_value;  // none: the graph must set it
  std::string unit;
  std::optional<double> min, max;           // numbers, integers and each array element
  std::vector<std::string> choices;         // strings: allowed values (empty = any)
  std::string description;

  bool required() const { return !default_value.has_value(); }

  static ParamSpec boolean(std::string n, bool d) { return make(std::move(n), ParamType::boolean, d); }
  static ParamSpec integer(std::string n, std::int64_t d) { return make(std::move(n), ParamType::integer, d); }
  static ParamSpec number(std::string n, double d) { return make(std::move(n), ParamType::number, d); }
  static ParamSpec string(std::string n, std::string d) {
    return make(std::move(n), ParamType::string, std::move(d));
  }
  static ParamSpec numbers(std::string n, std::vector<double> d) {
    return make(std::move(n), ParamType::number_array, std::move(d));
  }
  static ParamSpec json(std::string n, std::string default_text) {
    return make(std::move(n), ParamType::json, JsonText{std::move(default_text)});
  }
  // A parameter without a default: the graph has to give it.
  static ParamSpec required_param(std::string n, ParamType t) {
    ParamSpec p;
    p.name = std::move(n);
    p.type = t;
    return p;
  }

  ParamSpec& in_unit(std::string u) { unit = std::move(u); return *this; }
  ParamSpec& range(double lo, double hi) { min = lo; max = hi; return *this; }
  ParamSpec& at_least(double lo) { min = lo; return *this; }
  ParamSpec& one_of(std::vector<std::string> c) { choices = std::move(c); return *this; }
  ParamSpec& doc(std::string d) { description = std::move(d); return *this; }

 private:
  static ParamSpec make(std::string n, ParamType t, ParamValue d) {
    ParamSpec p;
    p.name = std::move(n);
    p.type = t;
    p.default_value = std::move(d);
    return p;
  }
};

// Two number parameters that must keep their order (a minimum and its maximum): lower <= upper,
// or lower < upper when strict. The host checks every node's values when it validates a graph.
// A NaN value (the "off" of an optional bound) satisfies it.
struct ParamConstraint {
  std::string lower, upper;
  bool strict = false;

  // Empty when the order holds; else what is wrong, naming both parameters and their values.
  std::string violation(const Params& p) const {
    if (!p.has(lower) || !p.has(upper)) return {};
    const double a = p.number(lower), b = p.number(upper);
    if (a != a || b != b) return {};  // NaN: a bound that is off keeps every order
    if (strict ? a < b : a <= b) return {};
    std::ostringstream s;
    s << "parameter '" << lower << "' (" << a << ") must be " << (strict ? "below" : "at most") << " '" << upper
      << "' (" << b << ")";
    return s.str();
  }
};

// When a node steps, and (latency, ABI 2.1) when what a step publishes is delivered.
struct TriggerSpec {
  enum class Kind { periodic, on_input, latency, deadline };
  Kind kind = Kind::periodic;
  // periodic: name of the number parameter that holds the rate in Hz; on_input: the input port;
  // latency: name of the number parameter that holds the latency in seconds; deadline: name of
  // the number parameter that holds the step deadline in seconds (0: none).
  std::string ref;
};

// What validation knows of a node before any plugin object exists (Manifest::check, ABI 2.4):
// its parameters, the types its ports carry and where its files are. A check throws BadInput
// (brickyard/context.hpp) naming the parameter, as configure would.
class CheckView {
 public:
  virtual ~CheckView() = default;
  virtual const Params& params() const = 0;
  // The type a port carries: its declared one, or for a port of any type its wire's ("" when it
  // is not wired); that type's IDL text (null when unknown).
  virtual const std::string& port_type(std::string_view port) const = 0;
  virtual const char* port_idl(std::string_view port) const = 0;
  // A file named in a parameter, found as Context::find_file finds it.
  virtual std::string find_file(std::string_view path) const = 0;
};
using CheckFn = void (*)(const CheckView&);

struct Manifest {
  std::string name;      // "area.plugin_name", unique among loaded libraries
  std::string version;   // semantic version of the plugin
  std::string description;
  std::vector<PortSpec> ports;
  std::vector<ParamSpec> params;
  std::vector<TriggerSpec> triggers;
  std::vector<ParamConstraint> constraints;  // ABI 2: appended to the manifest
  CheckFn checker = nullptr;
  std::vector<std::string> roles;            // the roles it plays (brickyard/roles.hpp)

  Manifest() = default;
  Manifest(std::string n, std::string v) : name(std::move(n)), version(std::move(v)) {}

  Manifest& describe(std::string d) { description = std::move(d); return *this; }

  // Every port of a binding, and the triggers of those that step the node
  // (brickyard/port_binding.hpp): how a plugin declares its ports.
  template <class P> Manifest& with_ports(const PortBinding<P>& b);
  // A role the plugin plays (brickyard/roles.hpp): the host checks its ports fit the role's.
  Manifest& plays(std::string role) {
    roles.push_back(std::move(role));
    return *this;
  }

  template <class T>
  Manifest& input(std::string port, std::string doc = {}, bool required = true, std::uint32_t depth = 16) {
    ports.push_back({std::move(port), PortDirection::input, message_traits<T>::name, message_traits<T>::hash,
                     std::move(doc), required, depth});
    return *this;
  }
  // An input of any message type: the wire's, whatever it is (a generic checker or recorder).
  // Its samples arrive as CDR (Context::input_any); validation lets any output feed it. (ABI 2.3)
  Manifest& input_any(std::string port, std::string doc = {}, bool required = true, std::uint32_t depth = 16) {
    ports.push_back({std::move(port), PortDirection::input, kAnyMessageType, "", std::move(doc), required, depth});
    return *this;
  }
  // An output of any message type: the type of the inputs it is wired to (all of one type), or
  // the one a string parameter names (type_param, when the graph sets it: an output that feeds
  // only inputs of any type). The plugin publishes CDR (Context::output_any); the host decodes it
  // for typed readers. Declared as the type name "*" + type_param. (ABI 2.3)
  Manifest& output_any(std::string port, std::string doc = {}, std::string type_param = {}) {
    ports.push_back({std::move(port), PortDirection::output, kAnyMessageType + type_param, "", std::move(doc), false, 0});
    return *this;
  }
  template <class T>
  Manifest& output(std::string port, std::string doc = {}) {
    ports.push_back({std::move(port), PortDirection::output, message_traits<T>::name, message_traits<T>::hash,
                     std::move(doc), false, 0});
    return *this;
  }
  Manifest& param(ParamSpec p) { params.push_back(std::move(p)); return *this; }
  // Every parameter of a binding, and its constraints (brickyard/param_binding.hpp).
  template <class S> Manifest& parameters(const ParamBinding<S>& b);
  // Step the node at the rate (Hz) held by the named number parameter.
  Manifest& periodic(std::string rate_param) {
    triggers.push_back({TriggerSpec::Kind::periodic, std::move(rate_param)});
    return *this;
  }
  // Step the node when a sample arrives on the named input.
  Manifest& on_input(std::string port) {
    triggers.push_back({TriggerSpec::Kind::on_input, std::move(port)});
    return *this;
  }
  // On the sim clock, what a step publishes (and logs) is delivered this many seconds (the named
  // number parameter) after the step: a sensor's frame that is ready only once its sweep is
  // over, a computation that takes time. Its inputs are read at the step's instant. A periodic
  // node: at most one period, and no input trigger (the host checks). A node woken by its
  // inputs: what comes while its step is out waits, and wakes it once that step is done. On the
  // real clock a step's outputs go when it returns: its latency is the real one. (ABI 2.1)
  Manifest& delivered_after(std::string seconds_param) {
    triggers.push_back({TriggerSpec::Kind::latency, std::move(seconds_param)});
    return *this;
  }

  // The node's step deadline, wall time, is the named number parameter (seconds; 0: none): its
  // default is the plugin's, a graph changes it like any parameter, and a graph node's
  // "deadline_s" has the last word. A step longer than it fails the run; one stuck at twice it
  // ends the process, which a supervisor may restart (docs/reliability.md). (ABI 2.2)
  Manifest& step_deadline(std::string seconds_param) {
    triggers.push_back({TriggerSpec::Kind::deadline, std::move(seconds_param)});
    return *this;
  }

  // A check of what the plugin's configure would refuse, run by `brickyard validate` and before a
  // run starts, every node's together: a field path that the wire's type lacks, a script that does
  // not encode. It may read files the parameters name; it must have no other effect. (ABI 2.4)
  Manifest& check(CheckFn f) {
    checker = f;
    return *this;
  }

  const PortSpec* port(const std::string& n) const {
    for (const auto& p : ports)
      if (p.name == n) return &p;
    return nullptr;
  }
  const ParamSpec* param_spec(const std::string& n) const {
    for (const auto& p : params)
      if (p.name == n) return &p;
    return nullptr;
  }
};

}  // namespace brickyard
