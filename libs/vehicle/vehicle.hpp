#pragma once
// One description of the car, read from one file per car (data/vehicles/av21.json first):
// geometry, mass and inertia, steering, tyres, aero, powertrain, the planning envelope and where
// the antennas and LiDARs sit. The simulator, planning, control and brickyard-plan all take it
// from here; no vehicle constant is written anywhere else. Framework-free.
#include <array>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::vehicle {

// A problem with a vehicle file; what() starts with "<file>: <JSON pointer>:" where it can.
class VehicleFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Mount {
  std::array<double, 3> xyz{};      // m in base_link (rear-axle centre; x forward, y left, z up)
  std::array<double, 3> rpy_deg{};  // roll, pitch, yaw
};

// How the car's drive-by-wire is driven (the vehicle interface's maps, docs/vehicle-interface.md):
// an optional section of the file, since a simulated car needs none of it.
struct DriveByWire {
  std::string source;                 // where the numbers come from
  double max_brake_pressure_kpa = 0;  // the brake pressure a brake pedal of 1 commands (linear map)
  double tyre_radius = 0;             // m, rolling radius: wheel speed to engine speed
  double final_drive = 0;             // ratio after the gearbox
  std::vector<double> gear_ratios;    // first gear first
  double redline_rpm = 0;             // the engine's limit
};

struct Vehicle {
  std::string name, source;
  // Geometry: base_link is the rear axle's centre.
  double wheelbase = 0;           // m, axle to axle
  double lf = 0, lr = 0;          // m, centre of gravity to front / rear axle (lf + lr = wheelbase)
  double track_width = 0;         // m
  double front = 0, rear = 0;     // m of body ahead of / behind base_link
  double half_width = 0;          // m
  double mass = 0;                // kg
  double yaw_inertia = 0;         // kg m^2
  double steering_ratio = 0;      // hand wheel : road wheel
  double max_steer = 0;           // rad, road wheel
  double max_steer_rate = 0;      // rad/s, road wheel
  double steer_delay = 0;         // s
  std::string tyre;               // linear | pacejka
  double cornering_front = 0, cornering_rear = 0;  // N/rad
  double mu = 0;                  // friction coefficient
  double pacejka_c = 0, pacejka_e = 0;             // shape; B follows from the cornering stiffness
  double drag_area = 0;           // Cd * A, m^2
  double lift_area = 0;           // Cl * A (downforce), m^2
  double downforce_front = 0;     // share on the front axle
  double air_density = 0;         // kg/m^3
  double max_power = 0;           // W at the rear wheels
  double max_drive_force = 0;     // N
  double max_brake_force = 0;     // N, all four wheels
  double brake_front = 0;         // share of braking on the front axle
  double rolling_resistance = 0;
  // The envelope planning may use: top speed, lateral grip and braking with a margin.
  double v_max = 0, a_lat = 0, a_decel = 0;
  std::map<std::string, Mount> mounts;  // gnss_left, lidar_front, ...
  std::optional<DriveByWire> drive_by_wire;  // "drive_by_wire": absent for a car that is only simulated

  // The named mount; throws VehicleFileError naming the car and the mount when there is none.
  const Mount& mount(const std::string& name) const;
};

// The standard gravity, m/s^2: not a property of the car.
inline constexpr double gravity = 9.81;

// Parses a vehicle file's text; `name` (the file) starts every error.
Vehicle parse_vehicle(const std::string& text, const std::string& name);
Vehicle load_vehicle(const std::string& path);

}  // namespace brickyard::vehicle
