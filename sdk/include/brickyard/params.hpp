#pragma once
// Parameter values a node receives: validated against the manifest, defaults applied.
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace brickyard {

enum class ParamType { boolean, integer, number, string, number_array, json };

inline const char* to_string(ParamType t) {
  switch (t) {
    case ParamType::boolean: return "boolean";
    case ParamType::integer: return "integer";
    case ParamType::number: return "number";
    case ParamType::string: return "string";
    case ParamType::number_array: return "number_array";
    case ParamType::json: return "json";
  }
  return "?";
}

// A json-typed parameter is carried as its JSON text; the plugin parses what it needs.
struct JsonText {
  std::string text;
  bool operator==(const JsonText& o) const { return text == o.text; }
};

using ParamValue = std::variant<bool, std::int64_t, double, std::string, std::vector<double>, JsonText>;

class Params {
 public:
  void set(const std::string& name, ParamValue v) { values_[name] = std::move(v); }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  const std::map<std::string, ParamValue>& all() const { return values_; }

  bool boolean(const std::string& name) const { return get<bool>(name, "boolean"); }
  std::int64_t integer(const std::string& name) const { return get<std::int64_t>(name, "integer"); }
  // An integer parameter reads as a number too.
  double number(const std::string& name) const {
    const ParamValue& v = at(name);
    if (auto i = std::get_if<std::int64_t>(&v)) return static_cast<double>(*i);
    if (auto d = std::get_if<double>(&v)) return *d;
    throw std::invalid_argument("parameter '" + name + "' is not a number");
  }
  const std::string& string(const std::string& name) const { return get<std::string>(name, "string"); }
  const std::vector<double>& numbers(const std::string& name) const {
    return get<std::vector<double>>(name, "number_array");
  }
  const std::string& json(const std::string& name) const { return get<JsonText>(name, "json").text; }

 private:
  const ParamValue& at(const std::string& name) const {
    auto it = values_.find(name);
    if (it == values_.end()) throw std::invalid_argument("parameter '" + name + "' has no value");
    return it->second;
  }
  template <class T> const T& get(const std::string& name, const char* what) const {
    const T* p = std::get_if<T>(&at(name));
    if (!p) throw std::invalid_argument("parameter '" + name + "' is not a " + what);
    return *p;
  }
  std::map<std::string, ParamValue> values_;
};

}  // namespace brickyard
