#include "race_control_sim.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <map>

namespace brickyard::sim {

namespace {

using nlohmann::json;

const std::map<std::string, vi::TrackFlag> kTrackNames = {
    {"green", vi::TrackFlag::green}, {"yellow", vi::TrackFlag::yellow}, {"red", vi::TrackFlag::red}, {"orange", vi::TrackFlag::orange}};
const std::map<std::string, vi::VehicleFlag> kVehicleNames = {{"none", vi::VehicleFlag::none},
                                                              {"checkered", vi::VehicleFlag::checkered},
                                                              {"black", vi::VehicleFlag::black},
                                                              {"purple", vi::VehicleFlag::purple}};

// A code 0..15, named or given; "" or why not.
template <class Names, class Code>
std::string flag_code(const json& v, const Names& names, Code code_of, int& code) {
  if (v.is_string()) {
    const auto it = names.find(v.get<std::string>());
    if (it == names.end()) return "'" + v.get<std::string>() + "' is no flag of this field";
    code = code_of(it->second);
    return "";
  }
  if (!v.is_number_integer() || v.get<int64_t>() < 0 || v.get<int64_t>() > 15) return "a flag's name or a code 0..15";
  code = v.get<int>();
  return "";
}

std::string entry_problem(const json& e, double last_t, const vi::FlagCodes& c, FlagEntry& out, std::string& where) {
  where = "";
  if (!e.is_object()) return "an object {t, track_flag, vehicle_flag, target_speed_mph} or {t, silent}";
  for (const auto& [key, v] : e.items()) {
    if (key == "t" || key == "silent" || key == "track_flag" || key == "vehicle_flag" || key == "target_speed_mph") continue;
    where = "/" + key;
    return "no such field (t, track_flag, vehicle_flag, target_speed_mph, silent)";
  }
  where = "/t";
  if (!e.contains("t") || !e["t"].is_number() || !std::isfinite(e["t"].get<double>()) || e["t"].get<double>() < last_t)
    return "a time in s, at or after the entry before's";
  out.t = e["t"].get<double>();
  where = "/silent";
  if (e.contains("silent") && !e["silent"].is_boolean()) return "true or false";
  out.silent = e.value("silent", false);
  if (out.silent) {
    out.text = "silent";
    return "";
  }
  where = "/track_flag";
  if (!e.contains("track_flag")) return "missing (or \"silent\": true)";
  if (std::string why = flag_code(e["track_flag"], kTrackNames, [&](vi::TrackFlag f) { return vi::track_code_of(c, f); }, out.track_code); !why.empty()) return why;
  where = "/vehicle_flag";
  if (std::string why = flag_code(e.value("vehicle_flag", json("none")), kVehicleNames, [&](vi::VehicleFlag f) { return vi::vehicle_code_of(c, f); }, out.vehicle_code); !why.empty()) return why;
  where = "/target_speed_mph";
  const json mph = e.value("target_speed_mph", json(0));
  if (!mph.is_number_integer() || mph.get<int64_t>() < 0 || mph.get<int64_t>() > 255) return "a whole number of mph, 0..255";
  out.target_mph = mph.get<int>();
  out.track = vi::track_flag_for(c, out.track_code), out.vehicle = vi::vehicle_flag_for(c, out.vehicle_code);
  out.text = std::string(track_flag_name(out.track)) + " (" + std::to_string(out.track_code) + "), " + vehicle_flag_name(out.vehicle) +
             " (" + std::to_string(out.vehicle_code) + "), " + std::to_string(out.target_mph) + " mph";
  return "";
}

}  // namespace

std::optional<std::vector<FlagEntry>> parse_flag_script(const std::string& text, const vi::FlagCodes& codes, std::string& error) {
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_array() || j.empty()) {
    error = "a JSON list of flags, at least one";
    return std::nullopt;
  }
  std::vector<FlagEntry> out;
  for (size_t i = 0; i < j.size(); ++i) {
    FlagEntry e;
    std::string where;
    if (std::string why = entry_problem(j[i], out.empty() ? 0.0 : out.back().t, codes, e, where); !why.empty()) {
      error = "/" + std::to_string(i) + where + ": " + why;
      return std::nullopt;
    }
    out.push_back(std::move(e));
  }
  return out;
}

SimRaceControl::SimRaceControl(std::vector<FlagEntry> script, double frame_hz, int rank)
    : script_(std::move(script)), period_ns_(static_cast<int64_t>(std::llround(1e9 / frame_hz))), rank_(rank) {}

void SimRaceControl::station(double s) {
  // Forwards over the line, the station falls back from the track's length to about 0.
  if (last_s_ && *last_s_ - s > 100.0) ++laps_;
  last_s_ = s;
  lap_distance_ = s;
}

SimRaceControl::Tick SimRaceControl::step(int64_t now_ns) {
  Tick out;
  const double t = static_cast<double>(now_ns) * 1e-9;
  while (next_ < script_.size() && script_[next_].t <= t) now_ = &script_[next_++], announced_ = false;
  if (now_ && now_->silent) {
    if (!announced_) out.began = now_, announced_ = true;
    return out;
  }
  if (!now_ || now_ns < next_frame_ns_) return out;
  next_frame_ns_ = now_ns - next_frame_ns_ >= period_ns_ ? now_ns + period_ns_ : next_frame_ns_ + period_ns_;
  if (!announced_) out.began = now_, announced_ = true;
  vi::RaceSummary f;
  f.heartbeat = heartbeat_;
  heartbeat_ = (heartbeat_ + 1) % 16;
  f.track_code = now_->track_code, f.vehicle_code = now_->vehicle_code, f.target_mph = now_->target_mph;
  f.rank = rank_, f.lap = laps_ % 256;
  f.lap_distance_m = static_cast<int>(std::clamp(lap_distance_, 0.0, 65535.0));
  out.frame = f;
  return out;
}

}  // namespace brickyard::sim
