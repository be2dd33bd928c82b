#include "race_control.hpp"

#include "can_signal.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <utility>

namespace brickyard::vehicle_interface {

namespace {

constexpr const char* kSummary = "base_to_car_summary";
// The signals, spelt as the car's DBC spells them (data/vehicle_interface/CAN1-INDY-V14.dbc).
constexpr std::array<const char*, 7> kSignals = {"base_to_car_heartbeat", "track_flag", "veh_flag", "veh_rank",
                                                 "lap_count", "lap_distance", "round_target_speed"};

int value_of(const SignalValues& v, const char* name) { return static_cast<int>(std::lround(v.at(name))); }

}  // namespace

std::string flag_codes_problem(const FlagCodes& c, std::string& param) {
  const std::array<std::pair<const char*, int>, 4> track = {
      {{"track_flag_red", c.red}, {"track_flag_orange", c.orange}, {"track_flag_yellow", c.yellow}, {"track_flag_green", c.green}}};
  const std::array<std::pair<const char*, int>, 4> vehicle = {{{"vehicle_flag_none", c.vehicle_none},
                                                               {"vehicle_flag_black", c.black},
                                                               {"vehicle_flag_checkered", c.checkered},
                                                               {"vehicle_flag_purple", c.purple}}};
  for (const auto* group : {&track, &vehicle}) {
    for (size_t i = 0; i < group->size(); ++i) {
      const auto& [name, code] = (*group)[i];
      param = name;
      if (code < 0 || code > 15) return "code " + std::to_string(code) + " does not fit the 4-bit signal (0 to 15)";
      for (size_t j = 0; j < i; ++j)
        if ((*group)[j].second == code) return "code " + std::to_string(code) + " is '" + (*group)[j].first + "' already";
    }
  }
  for (size_t i = 1; i < vehicle.size(); ++i) {  // 0 reads as no vehicle flag: no other flag may have it
    if (vehicle[i].second != 0) continue;
    param = vehicle[i].first;
    return "code 0 reads as no vehicle flag";
  }
  param.clear();
  return "";
}

TrackFlag track_flag_for(const FlagCodes& c, int code) {
  if (code == c.green) return TrackFlag::green;
  if (code == c.yellow) return TrackFlag::yellow;
  if (code == c.red) return TrackFlag::red;
  if (code == c.orange) return TrackFlag::orange;
  return TrackFlag::unknown;
}

VehicleFlag vehicle_flag_for(const FlagCodes& c, int code) {
  if (code == c.vehicle_none || code == 0) return VehicleFlag::none;
  if (code == c.checkered) return VehicleFlag::checkered;
  if (code == c.black) return VehicleFlag::black;
  if (code == c.purple) return VehicleFlag::purple;
  return VehicleFlag::unknown;
}

int track_code_of(const FlagCodes& c, TrackFlag f) {
  switch (f) {
    case TrackFlag::green: return c.green;
    case TrackFlag::yellow: return c.yellow;
    case TrackFlag::red: return c.red;
    case TrackFlag::orange: return c.orange;
    default: return 0;
  }
}

int vehicle_code_of(const FlagCodes& c, VehicleFlag f) {
  switch (f) {
    case VehicleFlag::none: return c.vehicle_none;
    case VehicleFlag::checkered: return c.checkered;
    case VehicleFlag::black: return c.black;
    case VehicleFlag::purple: return c.purple;
    default: return 0;
  }
}

std::optional<RaceControlDbc> RaceControlDbc::make(const DbcDatabase& db, const std::string& file, std::string& error) {
  const DbcMessage* m = db.find(kSummary);
  if (!m) {
    error = file + ": no message " + kSummary + " (race control's flags: the vehicle interface needs it)";
    return std::nullopt;
  }
  const std::string at = file + ":" + std::to_string(m->line) + ": message " + kSummary;
  if (m->independent_signals || m->extended_multiplexing) {
    error = at + ": its signals cannot be unpacked (extended multiplexing)";
    return std::nullopt;
  }
  RaceControlDbc out;
  for (const char* name : kSignals) {
    const DbcSignal* s = m->find_signal(name);
    if (!s || s->multiplexer_value || s->value_type != SignalValueType::kInteger) {
      error = at + (s ? ": signal " + std::string(name) + " is multiplexed or not an integer" : " has no signal " + std::string(name));
      return std::nullopt;
    }
  }
  const std::optional<RawRange> r = raw_range(*m->find_signal(kSignals[0]));
  if (!r || r->lowest != 0 || r->highest < 1 || r->highest > 65535) {
    error = at + ": its heartbeat does not count from 0 (0 to at least 1, at most 65535)";
    return std::nullopt;
  }
  out.message_ = *m;
  out.heartbeat_modulus_ = static_cast<uint32_t>(r->highest) + 1;
  return out;
}

RaceSummaryRead RaceControlDbc::read(const CanFrame& f) const {
  RaceSummaryRead out;
  UnpackResult u = unpack_message(message_, f);
  out.error = std::move(u.error);
  out.out_of_range = std::move(u.out_of_range);
  if (!out.error.empty()) return out;
  const SignalValues& v = u.values;
  RaceSummary& s = out.summary;
  s.heartbeat = value_of(v, "base_to_car_heartbeat"), s.track_code = value_of(v, "track_flag");
  s.vehicle_code = value_of(v, "veh_flag"), s.rank = value_of(v, "veh_rank"), s.lap = value_of(v, "lap_count");
  s.lap_distance_m = value_of(v, "lap_distance"), s.target_mph = value_of(v, "round_target_speed");
  return out;
}

PackResult RaceControlDbc::pack(const RaceSummary& s) const {
  return pack_message(message_, {{"base_to_car_heartbeat", s.heartbeat % static_cast<int>(heartbeat_modulus_)},
                                 {"track_flag", s.track_code},
                                 {"veh_flag", s.vehicle_code},
                                 {"veh_rank", s.rank},
                                 {"lap_count", s.lap},
                                 {"lap_distance", s.lap_distance_m},
                                 {"round_target_speed", s.target_mph}});
}

RaceControlMonitor::RaceControlMonitor(RaceControlParams p, uint32_t heartbeat_modulus) : p_(p), heartbeat_(heartbeat_modulus) {}

std::string RaceControlMonitor::received(const RaceSummary& s, int64_t now_ns) {
  const bool first = state_.frames == 0;
  const TrackFlag track = track_flag_for(p_.codes, s.track_code);
  const VehicleFlag vehicle = vehicle_flag_for(p_.codes, s.vehicle_code);
  const bool changed = first || track != state_.track || vehicle != state_.vehicle || s.target_mph != state_.last.target_mph;
  std::string said;
  if (changed) {
    char text[200];
    std::snprintf(text, sizeof text, "race control: track flag %s -> %s (code %d), vehicle flag %s -> %s (code %d), target %d mph",
                  track_flag_name(state_.track), track_flag_name(track), s.track_code, vehicle_flag_name(state_.vehicle),
                  vehicle_flag_name(vehicle), s.vehicle_code, s.target_mph);
    said = text;
  }
  // A heartbeat that moved is a sign of life; one that repeats is a base station that is stuck.
  const CounterStep step = heartbeat_.check(static_cast<uint32_t>(s.heartbeat));
  if (step == CounterStep::repeated) ++state_.heartbeat_repeats;
  else state_.heartbeat_changed_ns = now_ns;
  if (step == CounterStep::skipped) ++state_.heartbeat_skips;
  ++state_.frames;
  state_.last = s;
  state_.track = track, state_.vehicle = vehicle;
  state_.target_speed_mps = s.target_mph * motion::kMetresPerSecondPerMph;
  return said;
}

double RaceControlMonitor::heartbeat_age_s(int64_t now_ns) const {
  return state_.heartbeat_changed_ns ? static_cast<double>(now_ns - *state_.heartbeat_changed_ns) * 1e-9 : -1.0;
}

std::string RaceControlMonitor::check(int64_t now_ns) {
  const double age = heartbeat_age_s(now_ns);
  const bool heard = age >= 0 && age <= p_.timeout_s;
  if (heard == state_.heard) return "";
  state_.heard = heard;
  if (heard) return "race control heard";
  ++state_.losses;
  char text[120];
  std::snprintf(text, sizeof text, "race control lost: its heartbeat unchanged for %g s", p_.timeout_s);
  return text;
}

}  // namespace brickyard::vehicle_interface
