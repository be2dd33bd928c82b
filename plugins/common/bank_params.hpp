#pragma once
// The banking parameters of a track source (sim.world, map.track_file): bound in one place so both
// describe a road the same way. Plugin-side (SDK); the profile itself is track::bank_profile. Each
// plugin's defaults come from the track::BankSpec in its settings.
#include <brickyard/plugin.hpp>

#include <nlohmann/json.hpp>

#include "track/banking.hpp"

#include <string>

namespace brickyard::plugins {

// Reads `[[s0, s1, degrees], ...]`; throws BadInput naming the parameter and the element.
inline std::vector<track::BankSpec::Range> parse_bank_segments(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  if (!j.is_array()) throw BadInput("parameter 'bank_segments': must be an array of [s0, s1, degrees]");
  std::vector<track::BankSpec::Range> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const auto& r = j[i];
    if (!r.is_array() || r.size() != 3 || !r[0].is_number() || !r[1].is_number() || !r[2].is_number())
      throw BadInput("parameter 'bank_segments' /" + std::to_string(i) + ": must be [s0, s1, degrees]");
    out.push_back({r[0].get<double>(), r[1].get<double>(), r[2].get<double>()});
  }
  return out;
}

// Binds bank_mode, bank_deg, bank_curvature_threshold, bank_transition_m and bank_segments to the
// track::BankSpec at `path` in the plugin's settings.
template <class S, class... M> void bind_bank(ParamBinding<S>& b, M... path) {
  using B = track::BankSpec;
  b.bind("bank_mode", path..., &B::mode).one_of({"none", "constant", "curvature", "segments", "file"})
      .doc("where the road is banked: nowhere, everywhere, in turns, in listed ranges of s, or as the track file's bank_deg column says");
  b.bind("bank_deg", path..., &B::degrees).in_unit("deg").range(-45, 45)
      .doc("bank angle raising the outside (IMS turns: 9 deg 12 min)");
  b.bind("bank_curvature_threshold", path..., &B::curvature_threshold).in_unit("1/m").range(0, 1)
      .doc("curvature mode: a point is in a turn above this curvature");
  b.bind("bank_transition_m", path..., &B::transition_m).in_unit("m").range(0, 1000).doc("length of the bank ramps");
  nlohmann::json segments = nlohmann::json::array();
  for (const auto& r : detail::member_at(b.defaults(), path...).segments) segments.push_back({r.s0, r.s1, r.degrees});
  b.bind_with(ParamSpec::json("bank_segments", segments.dump()).doc("segments mode: [[s0, s1, degrees], ...]"),
              [path...](const Params& p, S& s) {
                detail::member_at(s, path...).segments = parse_bank_segments(p.json("bank_segments"));
              });
}

}  // namespace brickyard::plugins
