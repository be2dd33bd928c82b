#include "json_samples.hpp"

#include <cmath>
#include <stdexcept>

namespace brickyard::testing {

std::vector<ScriptedSample> encode_script(const nlohmann::json& script, const cdr::CdrJson& idl, const std::string& type) {
  if (!script.is_array() || script.empty()) throw std::invalid_argument(": expected a list of samples, [{\"t\": S, \"msg\": {...}}, ...]");
  if (script.size() > 1000000) throw std::invalid_argument(": more than a million samples");
  bool stamped = false;  // whether the type has header.stamp_ns to fill
  try {
    stamped = idl.field_kind(type, cdr::parse_field_path("header.stamp_ns")) == "number";
  } catch (const std::invalid_argument&) {
  }
  std::vector<ScriptedSample> out;
  double last = 0;
  for (std::size_t k = 0; k < script.size(); ++k) {
    const std::string where = "/" + std::to_string(k);
    const nlohmann::json& s = script[k];
    if (!s.is_object() || !s.contains("t") || !s.contains("msg") || s.size() != 2)
      throw std::invalid_argument(where + ": expected {\"t\": SECONDS, \"msg\": {...}}");
    if (!s["t"].is_number()) throw std::invalid_argument(where + "/t: expected a number of seconds");
    const double t = s["t"].get<double>();
    if (!std::isfinite(t) || t < 0 || t > 1e7) throw std::invalid_argument(where + "/t: expected 0 to 1e7 s, found " + s["t"].dump());
    if (t < last) throw std::invalid_argument(where + "/t: " + s["t"].dump() + " s is before the sample above it");
    last = t;
    nlohmann::json msg = s["msg"];
    const auto t_ns = static_cast<std::int64_t>(std::llround(t * 1e9));
    if (stamped && msg.is_object() && !(msg.contains("header") && msg["header"].is_object() && msg["header"].contains("stamp_ns")))
      msg["header"]["stamp_ns"] = t_ns;
    try {
      out.push_back({t_ns, idl.encode(type, msg)});
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + "/msg" + e.what());
    }
  }
  return out;
}

}  // namespace brickyard::testing
