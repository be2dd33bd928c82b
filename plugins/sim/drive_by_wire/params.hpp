#pragma once
// sim.drive_by_wire's parameters and what they name, read the same way at validation and in
// configure: the mapping (the car's DBC and vehicle file, as the vehicle interface reads them) and
// the bus, parsed. Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "sim/common/drive_by_wire.hpp"
#include "sim/sensor_faults.hpp"
#include "vehicle_interface/bus/can_bus.hpp"
#include "vehicle_interface/mapping_param.hpp"

#include <optional>
#include <string>

namespace brickyard::sim {

namespace vi = brickyard::vehicle_interface;

// Its bus's faults: "deaf", nothing the vehicle interface sends is heard (the car's computer dead,
// or its cable cut, as a killed stack's process is: no goodbye); "mute", no report is sent.
inline const std::vector<std::string> kBusFaultTypes = {"deaf", "mute"};

struct Settings {
  std::string dbc = vi::default_dbc_file;
  std::string vehicle = plugins::default_vehicle_file;
  std::string bus, send_to;
  double report_hz = 100;
  SimDbwParams dbw;
  FaultSchedule faults{"[]", 1, kBusFaultTypes};  // as declared: no window
};

inline ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("dbc", &Settings::dbc).doc("the car's DBC (data/vehicle_interface/)");
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: the maps (steering ratio, drive_by_wire)");
  b.bind_required("bus", &Settings::bus).doc("udp://HOST:PORT: the command frames (cannelloni datagrams) come here");
  b.bind_required("send_to", &Settings::send_to).doc("udp://HOST:PORT: the reports go there");
  b.declare(ParamSpec::number("rate_hz", 500).in_unit("Hz").range(1, 10000).doc("how often the bus is read and the car commanded"));
  b.bind("report_hz", &Settings::report_hz).in_unit("Hz").range(1, 1000).doc("how often the reports are sent");
  b.bind("command_timeout_s", &Settings::dbw, &SimDbwParams::command_timeout_s).in_unit("s").range(0.005, 60)
      .doc("actuator commands stale this long: its own stop");
  b.bind("heartbeat_timeout_s", &Settings::dbw, &SimDbwParams::heartbeat_timeout_s).in_unit("s").range(0.005, 60)
      .doc("ct_report's counter still this long: its own stop, adlink_hb_lost reported");
  b.bind("first_command_timeout_s", &Settings::dbw, &SimDbwParams::first_command_timeout_s).in_unit("s").range(0.01, 3600);
  b.bind("timeout_brake", &Settings::dbw, &SimDbwParams::timeout_brake).range(0, 1).doc("the brake pedal of its own stop");
  b.bind_choice("stop_steering", {{"hold", false}, {"centre", true}}, &Settings::dbw, &SimDbwParams::centre_steering)
      .doc("its own stop's wheel: the last angle held, or centred");
  b.bind("loss", &Settings::dbw, &SimDbwParams::loss).range(0, 1).doc("share of the frames lost each way, at random (seeded)");
  b.bind_with(ParamSpec::json("faults", "[]")
                  .doc("windows of the run's time: deaf (nothing from the vehicle interface heard), mute (no report sent)"),
              [](const Params& p, Settings& s) { s.faults = read_faults(p, 1, kBusFaultTypes); });
  return b;
}

// Whether a window of that type is open at t (the run's time).
inline bool bus_fault(const FaultSchedule& faults, const char* type, double t) {
  for (const FaultWindow& w : faults.windows())
    if (w.type == type && w.active(t)) return true;
  return false;
}

inline vi::BusSpec bus_of(const Settings& s) {
  std::string error, param;
  std::optional<vi::BusSpec> bus = vi::parse_bus(s.bus, s.send_to, error, param);
  if (!bus) throw BadInput("parameter '" + param + "': " + error);
  if (bus->kind != vi::BusSpec::Kind::udp) throw BadInput("parameter 'bus': the simulator's bus is udp://HOST:PORT");
  return *bus;
}

inline void check(const CheckView& v) {
  const Settings s = bindings().read(v.params());
  vehicle::Vehicle car;
  vi::read_mapping(v, s.dbc, s.vehicle, car);
  bus_of(s);
}

}  // namespace brickyard::sim
