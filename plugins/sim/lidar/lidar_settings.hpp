#pragma once
// sim.lidar's parameters: where the sensor sits, how its rows fan out, its noise and faults.
#include <brickyard/plugin.hpp>

#include "vehicle_param.hpp"
#include "sim/common/scanner.hpp"
#include "sim/sensor_faults.hpp"

namespace brickyard::sim {

struct LidarSettings {
  std::uint8_t sensor_id = 0;
  std::string vehicle = plugins::default_vehicle_file;
  std::string vehicle_mount = "lidar_front";
  std::vector<double> mount, mount_rpy_deg;  // empty: the vehicle file's mount
  LidarRowsDeg rows;
  LidarSpec spec;  // columns, ranges, noise and dropout; the rest is computed in configure
  FaultSchedule faults{"[]", 1, kLidarFaultTypes};  // as declared: no window
  double other_car_height = 1.0;  // m: the other cars' bodywork, from the road up
};

inline ParamBinding<LidarSettings> lidar_bindings() {
  using L = LidarSpec;
  using R = LidarRowsDeg;
  ParamBinding<LidarSettings> b;
  b.bind("sensor_id", &LidarSettings::sensor_id).range(0, 255);
  b.declare(ParamSpec::number("rate_hz", 20).in_unit("Hz").range(0.1, 1000));  // the host's trigger only
  // The host's too (Manifest::delivered_after): a frame is delivered once its sweep is over.
  b.declare(ParamSpec::number("latency_s", 0.05).in_unit("s").range(0, 10)
                .doc("a frame, stamped at its scan, is delivered this long after it (sim clock): a sweep, 1 / rate_hz, "
                     "as a spinning LiDAR's frame is ready when its sweep ends; at most 1 / rate_hz"));
  plugins::bind_vehicle(b, &LidarSettings::vehicle).doc("the car's description file: where its LiDARs sit");
  b.bind("vehicle_mount", &LidarSettings::vehicle_mount).doc("the sensor's mount in the vehicle file");
  b.bind("mount", &LidarSettings::mount).in_unit("m").range(-100, 100).doc("sensor position in base_link, m (x, y, z); empty: vehicle_mount's");
  b.bind("mount_rpy_deg", &LidarSettings::mount_rpy_deg).in_unit("deg").range(-360, 360)
      .doc("sensor roll, pitch, yaw in base_link, deg; empty: vehicle_mount's");
  b.bind("h_fov_deg", &LidarSettings::rows, &R::h_fov_deg).in_unit("deg").range(1, 360);
  b.bind("columns", &LidarSettings::spec, &L::columns).range(1, 100000);
  b.bind("rows", &LidarSettings::rows, &R::rows).range(1, 1024);
  b.bind("v_min_deg", &LidarSettings::rows, &R::v_min_deg).in_unit("deg").range(-90, 90);
  b.bind("v_max_deg", &LidarSettings::rows, &R::v_max_deg).in_unit("deg").range(-90, 90);
  b.bind("row_spacing", &LidarSettings::rows, &R::row_spacing).one_of({"horizon", "uniform"})
      .doc("horizon: rows concentrated near 0 deg as on the Hydra; uniform: evenly spaced");
  b.bind("horizon_exponent", &LidarSettings::rows, &R::horizon_exponent).range(1, 10).doc("horizon spacing: elevation ~ |u|^exponent");
  b.bind("row_angles_deg", &LidarSettings::rows, &R::row_angles_deg).in_unit("deg").range(-90, 90)
      .doc("explicit row elevations, deg; overrides rows and spacing");
  b.bind("min_range", &LidarSettings::spec, &L::min_range).in_unit("m").range(0, 1000);
  b.bind("max_range", &LidarSettings::spec, &L::max_range).in_unit("m").range(1, 1000);
  b.bind("range_noise", &LidarSettings::spec, &L::range_noise).in_unit("m").range(0, 100).doc("1 sigma");
  b.bind("dropout", &LidarSettings::spec, &L::dropout).range(0, 1).doc("probability that a return is lost");
  b.bind("threads", &LidarSettings::spec, &L::threads).range(1, 2).doc("threads the columns are marched on (AVX2); the same bits");
  // The windows are parsed as the parameters are read: a bad one is refused naming its JSON pointer.
  b.bind_with(ParamSpec::json("faults", "[]").doc("windows: noise (range sigma x factor), frame_loss, freeze, dropout"),
              [](const Params& p, LidarSettings& s) { s.faults = read_faults(p, 1, kLidarFaultTypes); });
  b.bind("other_car_height", &LidarSettings::other_car_height).in_unit("m").range(0.2, 5)
      .doc("the other cars (other0..other3), boxes over the vehicle file's footprint: their height above the road");
  b.below("v_min_deg", "v_max_deg");
  return b;
}

}  // namespace brickyard::sim
