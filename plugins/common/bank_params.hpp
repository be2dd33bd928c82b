#pragma once
// The banking parameters of a track source (sim.world, map.track_file): declared and read in one
// place so both describe a road the same way. Plugin-side (SDK); the profile itself is
// track::bank_profile.
#include <brickyard/plugin.hpp>

#include <nlohmann/json.hpp>

#include "track/banking.hpp"

#include <string>

namespace brickyard::plugins {

inline Manifest with_bank_params(Manifest m, const std::string& default_mode, double default_deg) {
  return m
      .param(ParamSpec::string("bank_mode", default_mode).one_of({"none", "constant", "curvature", "segments"})
                 .doc("where the road is banked: nowhere, everywhere, in turns, or in listed ranges of s"))
      .param(ParamSpec::number("bank_deg", default_deg).in_unit("deg").range(-45, 45)
                 .doc("bank angle raising the outside (IMS turns: 9 deg 12 min)"))
      .param(ParamSpec::number("bank_curvature_threshold", 0.002).in_unit("1/m").at_least(0)
                 .doc("curvature mode: a point is in a turn above this curvature"))
      .param(ParamSpec::number("bank_transition_m", 100).in_unit("m").at_least(0).doc("length of the bank ramps"))
      .param(ParamSpec::json("bank_segments", "[]").doc("segments mode: [[s0, s1, degrees], ...]"));
}

// Throws BadInput naming the parameter when bank_segments is malformed.
inline track::BankSpec read_bank_params(const Params& p) {
  track::BankSpec b;
  b.mode = p.string("bank_mode");
  b.degrees = p.number("bank_deg");
  b.curvature_threshold = p.number("bank_curvature_threshold");
  b.transition_m = p.number("bank_transition_m");
  const auto j = nlohmann::json::parse(p.json("bank_segments"));
  if (!j.is_array()) throw BadInput("parameter 'bank_segments': must be an array of [s0, s1, degrees]");
  for (std::size_t i = 0; i < j.size(); ++i) {
    const auto& r = j[i];
    if (!r.is_array() || r.size() != 3 || !r[0].is_number() || !r[1].is_number() || !r[2].is_number())
      throw BadInput("parameter 'bank_segments' /" + std::to_string(i) + ": must be [s0, s1, degrees]");
    b.segments.push_back({r[0].get<double>(), r[1].get<double>(), r[2].get<double>()});
  }
  return b;
}

}  // namespace brickyard::plugins
