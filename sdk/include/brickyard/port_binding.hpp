#pragma once
// Ports declared once. A plugin keeps its ports as typed members of a struct and binds each to
// its name in one place; the one binding gives the manifest its PortSpecs (the message type from
// the member's type) and connects the members to the host's channels in configure. A port's
// name is written once, and a plugin cannot declare one type and read another: the member's
// type is both.
//
//   struct Ports {
//     Input<msgs::PointCloud> points;
//     Output<msgs::ClusterList> clusters;
//   };
//   static PortBinding<Ports> ports() {
//     PortBinding<Ports> b;
//     b.input("points", &Ports::points).doc("points to cluster").depth(4).steps();
//     b.output("clusters", &Ports::clusters).doc("clusters in the vehicle frame");
//     return b;
//   }
//   manifest():  Manifest(...).with_ports(ports())
//   configure(): io_ = ports().connect(ctx);
//
// Header-only, like ParamBinding: only the PortSpecs and triggers it adds to the Manifest cross
// the library boundary.
#include <brickyard/context.hpp>
#include <brickyard/manifest.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace brickyard {

// One declared port, or a numbered array of them ("lidar0", "lidar1", ...): refine it with the
// chained calls. Inputs are required and keep 16 samples unless told otherwise.
class PortDecl {
 public:
  PortDecl& doc(std::string d) {
    for (auto& s : specs_) s.description = d;
    return *this;
  }
  // The graph may leave this input unwired (Input::connected() tells the plugin).
  PortDecl& optional() {
    for (auto& s : specs_) s.required = false;
    return *this;
  }
  // An array of inputs: the first `n` must be wired, the others may be.
  PortDecl& required_first(std::size_t n) {
    for (std::size_t i = 0; i < specs_.size(); ++i) specs_[i].required = i < n;
    return *this;
  }
  // Samples kept before the oldest is dropped.
  PortDecl& depth(std::uint32_t n) {
    for (auto& s : specs_) s.depth = n;
    return *this;
  }
  // Each sample that arrives steps the node (an on_input trigger).
  PortDecl& steps() {
    step_trigger_ = true;
    return *this;
  }
  // An output of any type (AnyOutput member) whose type the named string parameter may set.
  PortDecl& type_from(const std::string& param) {
    for (auto& s : specs_) s.type_name = kAnyMessageType + param;
    return *this;
  }

  const std::vector<PortSpec>& specs() const { return specs_; }
  bool step_trigger() const { return step_trigger_; }

 private:
  template <class P> friend class PortBinding;
  std::vector<PortSpec> specs_;
  bool step_trigger_ = false;
};

namespace detail {

template <class M> struct port_kind;
template <class T> struct port_kind<Input<T>> {
  static constexpr PortDirection direction = PortDirection::input;
  static const char* type_name() { return message_traits<T>::name; }
  static const char* type_hash() { return message_traits<T>::hash; }
  static Input<T> connect(Context& ctx, std::string_view port) { return ctx.input<T>(port); }
};
template <class T> struct port_kind<Output<T>> {
  static constexpr PortDirection direction = PortDirection::output;
  static const char* type_name() { return message_traits<T>::name; }
  static const char* type_hash() { return message_traits<T>::hash; }
  static Output<T> connect(Context& ctx, std::string_view port) { return ctx.output<T>(port); }
};
template <> struct port_kind<AnyInput> {
  static constexpr PortDirection direction = PortDirection::input;
  static const char* type_name() { return kAnyMessageType; }
  static const char* type_hash() { return ""; }
  static AnyInput connect(Context& ctx, std::string_view port) { return ctx.input_any(port); }
};
template <> struct port_kind<AnyOutput> {
  static constexpr PortDirection direction = PortDirection::output;
  static const char* type_name() { return kAnyMessageType; }
  static const char* type_hash() { return ""; }
  static AnyOutput connect(Context& ctx, std::string_view port) { return ctx.output_any(port); }
};

template <class M> PortSpec port_spec(std::string name) {
  using K = port_kind<M>;
  PortSpec s;
  s.name = std::move(name);
  s.direction = K::direction;
  s.type_name = K::type_name();
  s.type_hash = K::type_hash();
  if (K::direction == PortDirection::output) {
    s.required = false;
    s.depth = 0;
  }
  return s;
}

}  // namespace detail

template <class P> class PortBinding {
 public:
  // The input (Input<T> or AnyInput member) named `name`.
  template <class M> PortDecl& input(std::string name, M P::*member) {
    static_assert(detail::port_kind<M>::direction == PortDirection::input, "input() binds an Input<T> or AnyInput member");
    return add_one<M>(std::move(name), member);
  }
  // The output (Output<T> or AnyOutput member) named `name`.
  template <class M> PortDecl& output(std::string name, M P::*member) {
    static_assert(detail::port_kind<M>::direction == PortDirection::output, "output() binds an Output<T> or AnyOutput member");
    return add_one<M>(std::move(name), member);
  }
  // N inputs (or outputs) of one type, named prefix0 .. prefix{N-1}.
  template <class M, std::size_t N> PortDecl& inputs(const std::string& prefix, std::array<M, N> P::*member) {
    static_assert(detail::port_kind<M>::direction == PortDirection::input, "inputs() binds an array of Input<T>");
    return add_array<M, N>(prefix, member);
  }
  template <class M, std::size_t N> PortDecl& outputs(const std::string& prefix, std::array<M, N> P::*member) {
    static_assert(detail::port_kind<M>::direction == PortDirection::output, "outputs() binds an array of Output<T>");
    return add_array<M, N>(prefix, member);
  }
  template <class M, std::size_t N> PortDecl& inputs(const std::string& prefix, M (P::*member)[N]) {
    static_assert(detail::port_kind<M>::direction == PortDirection::input, "inputs() binds an array of Input<T>");
    return add_array<M, N>(prefix, member);
  }

  // Appends the ports, and an on_input trigger for each port that steps(), to a manifest
  // (Manifest::with_ports calls this).
  void declare_in(Manifest& m) const {
    for (const auto& e : entries_)
      for (const auto& s : e.decl.specs()) m.ports.push_back(s);
    for (const auto& e : entries_)
      if (e.decl.step_trigger())
        for (const auto& s : e.decl.specs()) m.on_input(s.name);
  }

  // The struct, each member connected to its port's channel.
  P connect(Context& ctx) const {
    P p{};
    connect(ctx, p);
    return p;
  }
  // Connects the members of an existing object (a plugin that binds its own members).
  void connect(Context& ctx, P& p) const {
    for (const auto& e : entries_) e.connect(ctx, p);
  }

 private:
  struct Entry {
    PortDecl decl;
    std::function<void(Context&, P&)> connect;
  };

  template <class M> PortDecl& add_one(std::string name, M P::*member) {
    PortDecl d;
    d.specs_.push_back(detail::port_spec<M>(name));
    return add(std::move(d), [name, member](Context& ctx, P& p) { p.*member = detail::port_kind<M>::connect(ctx, name); });
  }
  template <class M, std::size_t N, class A> PortDecl& add_array(const std::string& prefix, A P::*member) {
    PortDecl d;
    for (std::size_t i = 0; i < N; ++i) d.specs_.push_back(detail::port_spec<M>(prefix + std::to_string(i)));
    return add(std::move(d), [prefix, member](Context& ctx, P& p) {
      for (std::size_t i = 0; i < N; ++i) (p.*member)[i] = detail::port_kind<M>::connect(ctx, prefix + std::to_string(i));
    });
  }
  PortDecl& add(PortDecl d, std::function<void(Context&, P&)> connect) {
    for (const auto& e : entries_)
      for (const auto& s : e.decl.specs())
        for (const auto& n : d.specs())
          if (s.name == n.name) throw std::logic_error("port '" + n.name + "' bound twice");
    entries_.push_back({std::move(d), std::move(connect)});  // a deque keeps references valid
    return entries_.back().decl;
  }

  std::deque<Entry> entries_;
};

template <class P> Manifest& Manifest::with_ports(const PortBinding<P>& b) {
  b.declare_in(*this);
  return *this;
}

}  // namespace brickyard
