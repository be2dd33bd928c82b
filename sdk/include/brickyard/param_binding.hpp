#pragma once
// Parameters declared once. A plugin binds each parameter to a member of a settings struct (its
// algorithm's parameter struct, or a small struct of its own that nests it); the one binding
// gives the manifest its ParamSpec — the type from the member's type, the default from the
// struct's initialiser — and fills the struct from the validated values. A parameter's name is
// written in one place, so a renamed parameter cannot be declared under one name and read under
// another.
//
//   static ParamBinding<ClusterParams> bindings() {
//     ParamBinding<ClusterParams> b;
//     b.bind("tolerance", &ClusterParams::tolerance).in_unit("m").range(0.01, 100);
//     b.bind("min_size", &ClusterParams::min_size).range(1, 1e7);
//     b.bind("max_size", &ClusterParams::max_size).range(1, 1e7);
//     b.not_above("min_size", "max_size");   // checked by `brickyard validate`
//     return b;
//   }
//   manifest():  Manifest(...).parameters(bindings())
//   configure(): const ClusterParams c = bindings().read(ctx.params());
//
// Header-only: the binding never crosses the library boundary, only the ParamSpecs and the
// ParamConstraints it adds to the Manifest do.
#include <brickyard/context.hpp>
#include <brickyard/manifest.hpp>

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace brickyard {

namespace detail {

// obj.*m0.*m1... : the member a path of pointers to members names, outermost first.
template <class T, class M, class... Ms> auto& member_at(T& obj, M m, Ms... ms) {
  if constexpr (sizeof...(Ms) == 0) return obj.*m;
  else return member_at(obj.*m, ms...);
}

// The type of that member.
template <class S, class... M>
using member_t = std::remove_reference_t<decltype(member_at(std::declval<S&>(), std::declval<M>()...))>;

template <class T> constexpr bool always_false = false;
template <class T> struct is_optional : std::false_type {};
template <class T> struct is_optional<std::optional<T>> : std::true_type {};

// A float default shown and stored as the shortest decimal that reads back as the same float
// (0.35f declares 0.35, not 0.3499999940395355): reading it into the float member gives back the
// struct's value bit for bit.
inline double float_as_decimal(float f) {
  char buf[64];
  auto r = std::to_chars(buf, buf + sizeof buf - 1, f);
  *r.ptr = '\0';
  return std::strtod(buf, nullptr);
}

// The parameter type a member of type T is declared as, and its default value.
template <class T> ParamType param_type_of() {
  if constexpr (std::is_same_v<T, bool>) return ParamType::boolean;
  else if constexpr (std::is_integral_v<T>) return ParamType::integer;
  else if constexpr (std::is_floating_point_v<T>) return ParamType::number;
  else if constexpr (std::is_same_v<T, std::string>) return ParamType::string;
  else if constexpr (std::is_same_v<T, std::vector<double>>) return ParamType::number_array;
  else if constexpr (std::is_same_v<T, std::optional<double>>) return ParamType::number;
  else static_assert(always_false<T>, "bind a member of type bool, an integer, a floating point, std::string, "
                                      "std::vector<double> or std::optional<double>");
}
template <class T> ParamValue param_value_of(const T& v) {
  if constexpr (std::is_same_v<T, bool>) return v;
  else if constexpr (std::is_integral_v<T>) return static_cast<std::int64_t>(v);
  else if constexpr (std::is_same_v<T, float>) return float_as_decimal(v);
  else if constexpr (std::is_floating_point_v<T>) return static_cast<double>(v);
  else if constexpr (is_optional<T>::value) return v ? *v : std::numeric_limits<double>::quiet_NaN();
  else return v;
}
template <class T> void read_param(const Params& p, const std::string& name, T& out) {
  if constexpr (std::is_same_v<T, bool>) out = p.boolean(name);
  else if constexpr (std::is_integral_v<T>) out = static_cast<T>(p.integer(name));
  else if constexpr (std::is_floating_point_v<T>) out = static_cast<T>(p.number(name));
  else if constexpr (std::is_same_v<T, std::string>) out = p.string(name);
  else if constexpr (is_optional<T>::value) {
    const double v = p.number(name);
    out = v == v ? std::optional<double>(v) : std::nullopt;  // NaN: off
  } else out = p.numbers(name);
}

}  // namespace detail

template <class S> class ParamBinding {
 public:
  explicit ParamBinding(S defaults = S{}) : defaults_(std::move(defaults)) {}

  // The parameter `name` read into the member at `path` (one or more pointers to members,
  // outermost first). Its type follows the member's type; its default is the member's value in
  // the defaults struct. A std::optional<double> member is a number whose NaN means "off"
  // (an empty optional, and NaN as its default when the struct leaves it empty). Refine the returned spec with in_unit(), range(), one_of(), doc().
  template <class... M> ParamSpec& bind(std::string name, M... path) {
    using T = detail::member_t<S, M...>;
    ParamSpec spec = ParamSpec::required_param(name, detail::param_type_of<T>());
    spec.default_value = detail::param_value_of<T>(detail::member_at(defaults_, path...));
    return add(std::move(spec), [name, path...](const Params& p, S& s) {
      detail::read_param(p, name, detail::member_at(s, path...));
    });
  }

  // As bind(), without a default: the graph has to set it.
  template <class... M> ParamSpec& bind_required(std::string name, M... path) {
    ParamSpec& spec = bind(std::move(name), path...);
    spec.default_value.reset();
    return spec;
  }

  // A json parameter whose text (compact, as validated) goes into a std::string member.
  template <class... M> ParamSpec& bind_json(std::string name, M... path) {
    static_assert(std::is_same_v<detail::member_t<S, M...>, std::string>, "bind_json needs a std::string member");
    ParamSpec spec = ParamSpec::json(name, detail::member_at(defaults_, path...));
    return add(std::move(spec), [name, path...](const Params& p, S& s) { detail::member_at(s, path...) = p.json(name); });
  }

  // A string parameter naming one of `options`; the member receives the value paired with the
  // name. The default is the name whose value the defaults struct holds.
  template <class... M>
  ParamSpec& bind_choice(std::string name, std::vector<std::pair<std::string, detail::member_t<S, M...>>> options,
                         M... path) {
    std::vector<std::string> names;
    const std::string* def = nullptr;
    for (const auto& [n, v] : options) {
      names.push_back(n);
      if (!def && v == detail::member_at(defaults_, path...)) def = &n;
    }
    if (!def) throw std::logic_error("parameter '" + name + "': the default value is none of its choices");
    ParamSpec spec = ParamSpec::string(name, *def).one_of(names);
    return add(std::move(spec), [name, options = std::move(options), path...](const Params& p, S& s) {
      const std::string& chosen = p.string(name);
      for (const auto& [n, v] : options)
        if (n == chosen) {
          detail::member_at(s, path...) = v;
          return;
        }
      throw BadInput("parameter '" + name + "': \"" + chosen + "\" is not one of its choices");
    });
  }

  // For what a member cannot hold as it is (a unit converted, a JSON document parsed): the spec
  // and the code that reads it, still side by side. `read` may throw BadInput.
  ParamSpec& bind_with(ParamSpec spec, std::function<void(const Params&, S&)> read) {
    return add(std::move(spec), std::move(read));
  }

  // A parameter only the host reads (a periodic trigger's rate the plugin never uses).
  ParamSpec& declare(ParamSpec spec) { return add(std::move(spec), nullptr); }

  // Two number parameters that must keep their order: lower <= upper (strictly below with
  // below()). The host checks it when it validates the graph, before any node is built.
  ParamBinding& not_above(std::string lower, std::string upper) {
    constraints_.push_back({std::move(lower), std::move(upper), false});
    return *this;
  }
  ParamBinding& below(std::string lower, std::string upper) {
    constraints_.push_back({std::move(lower), std::move(upper), true});
    return *this;
  }

  // Appends the specs and constraints to a manifest (Manifest::parameters calls this).
  void declare_in(Manifest& m) const {
    for (const auto& e : entries_) m.param(e.spec);
    for (const auto& c : constraints_) m.constraints.push_back(c);
  }

  // The struct, each bound member read from validated parameters. A parameter `p` lacks keeps
  // the defaults struct's value (the host always passes every one; a unit test passes what it
  // changes). Throws BadInput when a constraint does not hold, which the host has already checked
  // for graphs; a unit test calling read() directly meets the same rule.
  S read(const Params& p) const {
    for (const auto& c : constraints_)
      if (auto e = c.violation(p); !e.empty()) throw BadInput(e);
    S s = defaults_;
    for (const auto& e : entries_)
      if (e.read && p.has(e.spec.name)) e.read(p, s);
    return s;
  }

  const S& defaults() const { return defaults_; }

 private:
  struct Entry {
    ParamSpec spec;
    std::function<void(const Params&, S&)> read;
  };
  ParamSpec& add(ParamSpec spec, std::function<void(const Params&, S&)> read) {
    for (const auto& e : entries_)
      if (e.spec.name == spec.name) throw std::logic_error("parameter '" + spec.name + "' bound twice");
    entries_.push_back({std::move(spec), std::move(read)});  // a deque keeps references valid
    return entries_.back().spec;
  }

  S defaults_;
  std::deque<Entry> entries_;
  std::vector<ParamConstraint> constraints_;
};

template <class S> Manifest& Manifest::parameters(const ParamBinding<S>& b) {
  b.declare_in(*this);
  return *this;
}

}  // namespace brickyard
