#pragma once
// vehicle_interface.raptor_dbw's parameters and what they name, read the same way at validation
// (Manifest::check) and in configure: the DBC and the vehicle file read and held against each
// other, the bus parsed (not opened: that is configure's). Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "vehicle_interface/bus/can_bus.hpp"
#include "vehicle_interface/common/raptor_interface.hpp"
#include "vehicle_interface/mapping_param.hpp"
#include "vehicle_interface/race_control_param.hpp"

#include "control/vehicle_tracking.hpp"

#include <optional>
#include <string>

namespace brickyard::vehicle_interface {

// The frames output: raw and decoded by the DBC, raw alone, or nothing.
enum class FramesOut { none, raw, decoded };

struct Settings {
  std::string dbc = default_dbc_file;
  std::string vehicle = plugins::default_vehicle_file;
  std::string bus, send_to, race_control_bus;
  double brake_hz = 100, accelerator_hz = 100, steering_hz = 100, gear_hz = 100, ct_report_hz = 100;
  double status_hz = 50;
  FramesOut frames = FramesOut::decoded;
  bool stop_on_path = true;
  PathStopParams path_stop;
  RaptorInterfaceParams iface;
};

inline ParamBinding<Settings> bindings() {
  using I = RaptorInterfaceParams;
  using W = DbwWatchdogParams;
  using G = ShiftParams;
  ParamBinding<Settings> b;
  b.bind("dbc", &Settings::dbc).doc("the car's DBC (data/vehicle_interface/)");
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: steering ratio, drive_by_wire (brake pressure, gears)");
  b.bind_required("bus", &Settings::bus).doc("can://IFNAME (SocketCAN), or udp://HOST:PORT to receive cannelloni datagrams on");
  b.bind("send_to", &Settings::send_to).doc("udp:// bus: where the frames go, udp://HOST:PORT");
  b.declare(ParamSpec::number("rate_hz", 500).in_unit("Hz").range(1, 10000).doc("how often the bus is polled and the commands due are sent"));
  for (auto [name, member] : {std::pair{"brake_hz", &Settings::brake_hz}, {"accelerator_hz", &Settings::accelerator_hz},
                              {"steering_hz", &Settings::steering_hz}, {"gear_hz", &Settings::gear_hz}, {"ct_report_hz", &Settings::ct_report_hz}})
    b.bind(name, member).in_unit("Hz").range(1, 1000).doc("the rate of this command on the bus");
  b.bind_choice("frames", {{"decoded", FramesOut::decoded}, {"raw", FramesOut::raw}, {"none", FramesOut::none}}, &Settings::frames)
      .doc("output frames: every frame written and read, with its signals decoded by the DBC (decoded), without them (raw), or none");
  b.bind("status_hz", &Settings::status_hz).in_unit("Hz").range(1, 1000).doc("how often VehicleStatus is published");
  b.bind("command_timeout_s", &Settings::iface, &I::watchdog, &W::timeout_s).in_unit("s").range(0.005, 10)
      .doc("commands older than this: throttle off, brake to a stop");
  b.bind("first_command_timeout_s", &Settings::iface, &I::watchdog, &W::first_timeout_s).in_unit("s").range(0.01, 3600)
      .doc("no command this long after the start: the same");
  b.bind("stop_decel_mps2", &Settings::iface, &I::watchdog, &W::stop_decel_mps2).in_unit("m/s^2").range(0.5, 20)
      .doc("the stop's deceleration by the brakes alone");
  b.bind_choice("stop_steering", {{"path", true}, {"hold", false}}, &Settings::stop_on_path)
      .doc("the stop's wheel: along the last path (its inputs path and estimate wired), else held at the last command");
  b.bind("path_stop_decel_mps2", &Settings::path_stop, &PathStopParams::decel_mps2).in_unit("m/s^2").range(0.5, 20)
      .doc("a stop along the path brakes at least this hard where the grip allows (short: the estimate's heading error grows with its length)");
  b.bind("stop_edge_room_m", &Settings::path_stop, &PathStopParams::line, &StopLineParams::edge_room_m).in_unit("m").range(0, 20)
      .doc("with the map wired: the stop's line keeps the car's centre this far from the edges at the trip (less where the path has less)");
  b.bind("stop_heading_doubt_deg", &Settings::path_stop, &PathStopParams::line, &StopLineParams::heading_doubt_deg).in_unit("deg").range(0, 10)
      .doc("with the map wired: the heading error the dead reckoning cannot see; the room to the edges grows by its tangent per metre stopped");
  b.bind("stopped_speed_mps", &Settings::iface, &I::watchdog, &W::stopped_speed_mps).in_unit("m/s").range(0, 5);
  b.bind("hold_stopped_s", &Settings::iface, &I::watchdog, &W::hold_s).in_unit("s").range(0, 60)
      .doc("standing this long after a stop: the heartbeat stops (the drive-by-wire's safety takes over)");
  b.bind("report_timeout_s", &Settings::iface, &I::report_timeout_s).in_unit("s").range(0.005, 60).doc("a report silent this long is named");
  b.bind("shift_up_rpm", &Settings::iface, &I::shift, &G::up_rpm).in_unit("rpm").range(100, 1e5);
  b.bind("shift_down_rpm", &Settings::iface, &I::shift, &G::down_rpm).in_unit("rpm").range(0, 1e5);
  b.bind("min_shift_interval_s", &Settings::iface, &I::shift, &G::min_interval_s).in_unit("s").range(0, 10);
  b.bind("fixed_gear", &Settings::iface, &I::shift, &G::fixed_gear).range(0, 16).doc("0: shift by rpm; N: hold gear N");
  b.bind("ct_state", &Settings::iface, &I::ct_state).range(0, 65535).doc("the team's state in ct_report (the event's rules give the codes)");
  b.bind("vehicle_number", &Settings::iface, &I::vehicle_number).range(0, 255).doc("ct_report's veh_num");
  b.bind("race_control_bus", &Settings::race_control_bus)
      .doc("udp://HOST:PORT: race control's frames come here, a peer of their own (the simulator's); empty: on the bus");
  b.bind("race_control_timeout_s", &Settings::iface, &I::race_control, &RaceControlParams::timeout_s).in_unit("s").range(0.01, 60)
      .doc("race control's heartbeat unchanged this long: race control lost (RaceControl.heard false)");
  bind_flag_codes(b, &Settings::iface, &I::race_control, &RaceControlParams::codes);
  b.not_above("shift_down_rpm", "shift_up_rpm");
  return b;
}

struct Setup {
  std::optional<VehicleCanMapping> mapping;
  DbcDatabase database;  // the whole DBC: the frames output decodes by it
  std::optional<RaceControlDbc> race_control;
  RaptorInterfaceParams params;
  control::TrackerParams stop_tracker;  // the stop along the last path's: the lqr law with the car's facts
  BusSpec bus;
  std::optional<drivers::SourceSpec> race_control_bus;  // none: race control's frames come on `bus`
};

// Everything the parameters name, read and checked; BadInput naming the parameter otherwise.
template <class Files> Setup read_setup(const Files& files, const Settings& s) {
  Setup out;
  vehicle::Vehicle car;
  out.database = load_car_dbc(files, s.dbc);  // read once: the mapping, race control and the frames output
  out.mapping.emplace(read_mapping(files, out.database, s.dbc, s.vehicle, car));
  out.params = s.iface;
  out.params.rates_hz = {s.brake_hz, s.accelerator_hz, s.steering_hz, s.gear_hz, s.ct_report_hz};
  out.params.watchdog.v_max_mps = car.v_max;
  out.stop_tracker.steer_law = control::SteerLaw::lqr;
  out.stop_tracker.lqr.r_steer = 200;       // the race graphs' path tracker's: a smooth wheel
  out.stop_tracker.command_latency = 0.01;  // the interface is at the bus: its own step and the frame's way
  control::apply_vehicle(out.stop_tracker, car);
  if (const ShiftProblem p = shift_problem(s.iface.shift, out.mapping->maps()); !p.what.empty())
    throw BadInput("parameter '" + p.param + "': " + p.what + " (" + s.vehicle + ")");
  std::string error, param;
  std::optional<BusSpec> bus = parse_bus(s.bus, s.send_to, error, param);
  if (!bus) throw BadInput("parameter '" + param + "': " + error);
  out.bus = *bus;
  out.race_control.emplace(read_race_control_dbc(out.database, s.dbc));
  check_flag_codes(s.iface.race_control.codes);
  if (!s.race_control_bus.empty()) {
    if (!s.race_control_bus.starts_with("udp://"))
      throw BadInput("parameter 'race_control_bus': '" + s.race_control_bus + "': udp://HOST:PORT (on a CAN bus race control's frames come on 'bus')");
    out.race_control_bus = parse_udp_address(s.race_control_bus, error);
    if (!out.race_control_bus) throw BadInput("parameter 'race_control_bus': " + error);
  }
  return out;
}

}  // namespace brickyard::vehicle_interface
