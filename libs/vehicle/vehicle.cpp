#include "vehicle.hpp"

#include "io/bounded_read.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace brickyard::vehicle {
namespace {

using json = nlohmann::json;

// Reads one object of the file, refusing keys it does not know (a misspelt key is never ignored).
class Section {
 public:
  Section(const json& j, std::string pointer, const std::string& file) : j_(j), ptr_(std::move(pointer)), file_(file) {
    if (!j_.is_object()) fail(ptr_, "expected an object");
  }
  ~Section() noexcept(false) {
    if (std::uncaught_exceptions()) return;
    for (auto it = j_.begin(); it != j_.end(); ++it)
      if (!seen_.count(it.key())) fail(ptr_ + "/" + it.key(), "unknown key");
  }
  double number(const std::string& key, double lo, double hi) {
    const json& v = at(key);
    if (!v.is_number()) fail(ptr_ + "/" + key, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi) {
      std::ostringstream m;
      m << "expected a number from " << lo << " to " << hi << ", found " << x;
      fail(ptr_ + "/" + key, m.str());
    }
    return x;
  }
  std::string string(const std::string& key) {
    const json& v = at(key);
    if (!v.is_string()) fail(ptr_ + "/" + key, "expected a string");
    return v.get<std::string>();
  }
  std::array<double, 3> triple(const json& v, const std::string& pointer) {
    if (!v.is_array() || v.size() != 3) fail(pointer, "expected [x, y, z]");
    std::array<double, 3> out{};
    for (std::size_t i = 0; i < 3; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) fail(pointer + "/" + std::to_string(i), "expected a number");
      out[i] = v[i].get<double>();
    }
    return out;
  }
  const json& at(const std::string& key) {
    if (!j_.contains(key)) fail(ptr_, "missing key \"" + key + "\"");
    seen_.insert(key);
    return j_.at(key);
  }
  const std::string& pointer() const { return ptr_; }
  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    throw VehicleFileError(file_ + ": " + (pointer.empty() ? "/" : pointer) + ": " + what);
  }

 private:
  const json& j_;
  std::string ptr_;
  const std::string& file_;
  std::set<std::string> seen_;
};

// Each read_* step reads one section of the file into v; its Section refuses unknown keys as the
// step ends, before the next section is read.
void read_geometry(Section& top, const std::string& file, Vehicle& v) {
  Section g(top.at("geometry"), "/geometry", file);
  v.wheelbase = g.number("wheelbase_m", 0.5, 10);
  v.lf = g.number("lf_m", 0.1, 10);
  v.lr = g.number("lr_m", 0.1, 10);
  if (std::abs(v.lf + v.lr - v.wheelbase) > 1e-6) g.fail("/geometry", "lf_m + lr_m must equal wheelbase_m");
  v.track_width = g.number("track_width_m", 0.3, 5);
  v.front = g.number("front_m", 0, 20);
  v.rear = g.number("rear_m", 0, 20);
  v.half_width = g.number("half_width_m", 0.1, 5);
}

void read_mass(Section& top, const std::string& file, Vehicle& v) {
  Section m(top.at("mass"), "/mass", file);
  v.mass = m.number("mass_kg", 1, 1e5);
  v.yaw_inertia = m.number("yaw_inertia_kgm2", 1, 1e7);
}

void read_steering(Section& top, const std::string& file, Vehicle& v) {
  Section s(top.at("steering"), "/steering", file);
  v.steering_ratio = s.number("ratio", 1, 100);
  v.max_steer = s.number("max_steer_rad", 0.01, 1.5);
  v.max_steer_rate = s.number("max_steer_rate_radps", 0.01, 100);
  v.steer_delay = s.number("delay_s", 0, 0.25);  // the LQR tracker plans over it and more, up to 0.3 s
}

void read_tyres(Section& top, const std::string& file, Vehicle& v) {
  Section t(top.at("tyres"), "/tyres", file);
  v.tyre = t.string("model");
  if (v.tyre != "linear" && v.tyre != "pacejka") t.fail("/tyres/model", "expected \"linear\" or \"pacejka\", found \"" + v.tyre + "\"");
  v.cornering_front = t.number("cornering_front_npr", 1, 1e8);
  v.cornering_rear = t.number("cornering_rear_npr", 1, 1e8);
  v.mu = t.number("mu", 0.1, 5);
  v.pacejka_c = t.number("pacejka_c", 0.1, 5);
  v.pacejka_e = t.number("pacejka_e", -10, 1);
}

void read_aero(Section& top, const std::string& file, Vehicle& v) {
  Section a(top.at("aero"), "/aero", file);
  v.drag_area = a.number("drag_area_m2", 0, 20);
  v.lift_area = a.number("lift_area_m2", 0, 50);
  v.downforce_front = a.number("downforce_front", 0, 1);
  v.air_density = a.number("air_density_kgpm3", 0.1, 5);
}

void read_powertrain(Section& top, const std::string& file, Vehicle& v) {
  Section p(top.at("powertrain"), "/powertrain", file);
  v.max_power = p.number("max_power_w", 0, 1e7);
  v.max_drive_force = p.number("max_drive_force_n", 0, 1e6);
  v.max_brake_force = p.number("max_brake_force_n", 0, 1e6);
  v.brake_front = p.number("brake_front", 0, 1);
  v.rolling_resistance = p.number("rolling_resistance", 0, 1);
}

// Needs the tyres and the powertrain read first.
void read_limits(Section& top, const std::string& file, Vehicle& v) {
  Section l(top.at("limits"), "/limits", file);
  v.v_max = l.number("v_max_mps", 1, 200);
  v.a_lat = l.number("a_lat_mps2", 0.5, 100);
  v.a_decel = l.number("a_decel_mps2", 0.1, 100);
  // The envelope is what the car can do without downforce: never more grip than its tyres have,
  // never more braking than its tyres or its brakes give. A car file that promises more would
  // have every planner drive it off the road.
  char why[160];
  const double grip = v.mu * gravity, brakes = v.max_brake_force / v.mass;
  if (v.a_lat > grip) {
    std::snprintf(why, sizeof why, "%g m/s^2 is more than the tyres' grip (mu %g x g = %.2f m/s^2)", v.a_lat, v.mu, grip);
    l.fail("/limits/a_lat_mps2", why);
  }
  if (v.a_decel > std::min(grip, brakes)) {
    std::snprintf(why, sizeof why, "%g m/s^2 is more than the car can brake (tyres %.2f, brakes %.2f m/s^2)", v.a_decel,
                  grip, brakes);
    l.fail("/limits/a_decel_mps2", why);
  }
}

// Each mount is [x, y, z], or {"xyz": [...], "rpy_deg": [...]}.
void read_mounts(Section& top, const std::string& file, Vehicle& v) {
  const json& mounts = top.at("mounts");
  if (!mounts.is_object()) top.fail("/mounts", "expected an object");
  for (auto it = mounts.begin(); it != mounts.end(); ++it) {
    const std::string ptr = "/mounts/" + it.key();
    Mount m;
    if (it->is_array()) {
      m.xyz = top.triple(*it, ptr);
    } else {
      Section s(*it, ptr, file);
      m.xyz = s.triple(s.at("xyz"), ptr + "/xyz");
      m.rpy_deg = s.triple(s.at("rpy_deg"), ptr + "/rpy_deg");
    }
    v.mounts[it.key()] = m;
  }
}

// Optional: the drive-by-wire's maps (a car that is only simulated has none). Gear ratios strictly
// decreasing from first gear: a gearbox whose gears do not go up cannot be shifted by rpm.
void read_drive_by_wire(Section& top, const std::string& file, Vehicle& v) {
  Section d(top.at("drive_by_wire"), "/drive_by_wire", file);
  DriveByWire w;
  w.source = d.string("source");
  w.max_brake_pressure_kpa = d.number("max_brake_pressure_kpa", 1, 1e5);
  w.tyre_radius = d.number("tyre_radius_m", 0.05, 2);
  w.final_drive = d.number("final_drive", 0.1, 50);
  const json& gears = d.at("gear_ratios");
  if (!gears.is_array() || gears.empty() || gears.size() > 16) d.fail("/drive_by_wire/gear_ratios", "expected 1 to 16 numbers");
  for (std::size_t i = 0; i < gears.size(); ++i) {
    const std::string ptr = "/drive_by_wire/gear_ratios/" + std::to_string(i);
    if (!gears[i].is_number() || !std::isfinite(gears[i].get<double>()) || gears[i].get<double>() <= 0 || gears[i].get<double>() > 50)
      d.fail(ptr, "expected a ratio above 0, at most 50");
    if (i > 0 && gears[i].get<double>() >= w.gear_ratios.back()) d.fail(ptr, "each gear's ratio must be below the one before");
    w.gear_ratios.push_back(gears[i].get<double>());
  }
  w.redline_rpm = d.number("redline_rpm", 100, 1e5);
  v.drive_by_wire = std::move(w);
}

}  // namespace

const Mount& Vehicle::mount(const std::string& n) const {
  auto it = mounts.find(n);
  if (it == mounts.end()) throw VehicleFileError("vehicle '" + name + "' has no mount \"" + n + "\"");
  return it->second;
}

Vehicle parse_vehicle(const std::string& text, const std::string& file) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::parse_error& e) {
    throw VehicleFileError(file + ": invalid JSON: " + e.what());
  }
  Vehicle v;
  Section top(j, "", file);
  v.name = top.string("name");
  if (j.contains("source")) v.source = top.string("source");
  read_geometry(top, file, v);
  read_mass(top, file, v);
  read_steering(top, file, v);
  read_tyres(top, file, v);
  read_aero(top, file, v);
  read_powertrain(top, file, v);
  read_limits(top, file, v);
  read_mounts(top, file, v);
  if (j.contains("drive_by_wire")) read_drive_by_wire(top, file, v);
  return v;
}

// A vehicle file is a few kB: 16 MiB is far past any, and a FIFO or /dev/zero is refused unread.
constexpr std::size_t kMaxVehicleBytes = std::size_t{16} << 20;

Vehicle load_vehicle(const std::string& path) {
  std::vector<std::uint8_t> bytes;
  std::string error;
  if (!io::read_regular_file(path, kMaxVehicleBytes, bytes, error)) throw VehicleFileError(error);
  return parse_vehicle(std::string(bytes.begin(), bytes.end()), path);
}

}  // namespace brickyard::vehicle
