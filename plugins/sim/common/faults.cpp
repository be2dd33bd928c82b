#include "faults.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace brickyard::sim {

FaultSchedule::FaultSchedule(const std::string& text, std::size_t dims, const std::vector<std::string>& allowed)
    : dims_(dims) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const std::exception& e) {
    throw FaultError(std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_array()) throw FaultError("/: must be an array of fault windows");
  for (std::size_t i = 0; i < j.size(); ++i) {
    const auto& o = j[i];
    const std::string at = "/" + std::to_string(i);
    if (!o.is_object()) throw FaultError(at + ": must be an object");
    FaultWindow w;
    auto num = [&](const char* key, bool required, double def) {
      if (!o.contains(key)) {
        if (required) throw FaultError(at + "/" + key + ": missing");
        return def;
      }
      if (!o[key].is_number()) throw FaultError(at + "/" + key + ": must be a number");
      double v = o[key].get<double>();
      if (!std::isfinite(v)) throw FaultError(at + "/" + key + ": must be finite");
      return v;
    };
    if (!o.contains("type") || !o["type"].is_string()) throw FaultError(at + "/type: missing or not a string");
    w.type = o["type"].get<std::string>();
    if (std::find(allowed.begin(), allowed.end(), w.type) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw FaultError(at + "/type: '" + w.type + "' is not one of: " + list);
    }
    w.start_s = num("start_s", true, 0);
    w.end_s = num("end_s", true, 0);
    if (w.end_s <= w.start_s) throw FaultError(at + "/end_s: must be after start_s");
    static const std::vector<std::string> known = {"type", "start_s", "end_s", "offset", "rate", "factor",
                                                    "probability", "magnitude", "fix_type"};
    for (auto it = o.begin(); it != o.end(); ++it)
      if (std::find(known.begin(), known.end(), it.key()) == known.end())
        throw FaultError(at + "/" + it.key() + ": unknown key");
    auto vec = [&](const char* key) {
      if (!o.contains(key)) throw FaultError(at + "/" + key + ": missing (" + std::to_string(dims) + " numbers)");
      const auto& a = o[key];
      if (!a.is_array() || a.size() != dims)
        throw FaultError(at + "/" + key + ": must be an array of " + std::to_string(dims) + " numbers");
      std::vector<double> v;
      for (const auto& x : a) {
        if (!x.is_number()) throw FaultError(at + "/" + key + ": must hold numbers");
        v.push_back(x.get<double>());
      }
      return v;
    };
    if (w.type == "bias") w.vec = vec("offset");
    if (w.type == "drift") w.vec = vec("rate");
    if (w.type == "noise" || w.type == "sigma") {
      w.factor = num("factor", true, 1);
      if (w.factor < 0) throw FaultError(at + "/factor: must be >= 0");
    }
    if (w.type == "spikes" || w.type == "frame_loss") {
      w.probability = num("probability", true, 0);
      if (w.probability < 0 || w.probability > 1) throw FaultError(at + "/probability: must be in [0, 1]");
    }
    if (w.type == "spikes") w.magnitude = num("magnitude", true, 0);
    if (o.contains("fix_type")) {
      double f = num("fix_type", false, 0);
      if (f != std::floor(f) || f < 0 || f > 3) throw FaultError(at + "/fix_type: must be 0, 1, 2 or 3");
      w.fix_type = static_cast<int>(f);
    }
    w_.push_back(std::move(w));
  }
}

FaultEffect FaultSchedule::at(double t, Rng& rng) const {
  FaultEffect e;
  e.offset.assign(dims_, 0.0);
  for (const auto& w : w_) {
    if (!w.active(t)) continue;
    if (w.fix_type) e.fix_type = w.fix_type;
    if (w.type == "bias") {
      for (std::size_t k = 0; k < dims_; ++k) e.offset[k] += w.vec[k];
    } else if (w.type == "drift") {
      for (std::size_t k = 0; k < dims_; ++k) e.offset[k] += w.vec[k] * (t - w.start_s);
    } else if (w.type == "noise") {
      e.noise_factor *= w.factor;
    } else if (w.type == "sigma") {
      e.sigma_factor *= w.factor;
    } else if (w.type == "freeze") {
      e.freeze = true;
    } else if (w.type == "dropout") {
      e.drop = true;
    } else if (w.type == "spikes") {
      if (rng.uniform() < w.probability) {
        // A spike of the given size in a random direction (the first two axes for vectors).
        double a = 2 * M_PI * rng.uniform();
        if (dims_ >= 2) {
          e.offset[0] += w.magnitude * std::cos(a);
          e.offset[1] += w.magnitude * std::sin(a);
        } else if (dims_ == 1) {
          e.offset[0] += w.magnitude * (std::cos(a) >= 0 ? 1 : -1);
        }
      }
    } else if (w.type == "frame_loss") {
      if (rng.uniform() < w.probability) e.drop = true;
    }
  }
  return e;
}

}  // namespace brickyard::sim
