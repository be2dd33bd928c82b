#pragma once
// sim.race_control's parameters and what they name, read the same way at validation and in
// configure: the script of flags, the codes it sends them with (the vehicle interface's
// parameters, the same defaults), base_to_car_summary in the car's DBC, where the frames go, and
// the judge's bounds. Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "sim/common/flag_judge.hpp"
#include "sim/common/race_control_sim.hpp"
#include "vehicle_interface/bus/can_bus.hpp"
#include "vehicle_interface/race_control_param.hpp"

#include <string>
#include <vector>

namespace brickyard::sim {

struct Settings {
  std::string dbc = vi::default_dbc_file;
  std::string send_to, script;
  double frame_hz = 10;
  int rank = 1;
  vi::FlagCodes codes;
  JudgeParams judge;
};

inline ParamBinding<Settings> bindings() {
  using J = JudgeParams;
  ParamBinding<Settings> b;
  b.bind("dbc", &Settings::dbc).doc("the car's DBC (data/vehicle_interface/): base_to_car_summary");
  b.bind_required("send_to", &Settings::send_to).doc("udp://HOST:PORT: the frames (cannelloni datagrams) go there: the interface's race_control_bus");
  b.bind_json("script", &Settings::script)
      .doc("the flags: a JSON list of {t, track_flag, vehicle_flag, target_speed_mph} or {t, silent: true} (docs/race-control.md)")
      .default_value.reset();  // required: the graph gives the script
  b.declare(ParamSpec::number("rate_hz", 100).in_unit("Hz").range(1, 10000).doc("how often the truth is judged and a frame may go out"));
  b.bind("frame_hz", &Settings::frame_hz).in_unit("Hz").range(0.1, 1000).doc("base_to_car_summary's rate, its heartbeat one more each frame");
  b.bind("rank", &Settings::rank).range(0, 15).doc("veh_rank sent");
  vi::bind_flag_codes(b, &Settings::codes);
  b.bind("decel_mps2", &Settings::judge, &J::decel_mps2).in_unit("m/s^2").range(0.5, 20)
      .doc("the judge: the deceleration the distances allowed are worked out at (control.system_manager's stop_decel_mps2)");
  b.bind("stop_margin", &Settings::judge, &J::stop_margin).range(0, 10).doc("the judge: a stop may take this share more than its distance");
  b.bind("speed_tolerance_mps", &Settings::judge, &J::speed_tolerance_mps).in_unit("m/s").range(0, 10)
      .doc("the judge: a yellow's target is reached within this");
  b.bind("stopped_speed_mps", &Settings::judge, &J::stopped_speed_mps).in_unit("m/s").range(0.01, 5);
  b.bind("silence_allowance_s", &Settings::judge, &J::silence_allowance_s).in_unit("s").range(0, 60)
      .doc("the judge: after race control falls silent the car may race on this long (the interface's race_control_timeout_s and a frame)");
  return b;
}

struct Setup {
  std::vector<FlagEntry> script;
  std::optional<vi::RaceControlDbc> dbc;
  drivers::SourceSpec send_to;
};

template <class Files> Setup read_setup(const Files& files, const Settings& s) {
  Setup out;
  vi::check_flag_codes(s.codes);
  std::string error;
  std::optional<std::vector<FlagEntry>> script = parse_flag_script(s.script, s.codes, error);
  if (!script) throw BadInput("parameter 'script'" + std::string(error.starts_with("/") ? " " : ": ") + error);
  out.script = std::move(*script);
  out.dbc.emplace(vi::read_race_control_dbc(files, s.dbc));
  std::optional<drivers::SourceSpec> to = vi::parse_udp_address(s.send_to, error);
  if (!to) throw BadInput("parameter 'send_to': " + error);
  out.send_to = *to;
  return out;
}

inline void check(const CheckView& v) { read_setup(v, bindings().read(v.params())); }

}  // namespace brickyard::sim
