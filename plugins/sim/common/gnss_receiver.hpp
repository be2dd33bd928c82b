#pragma once
// A simulated GNSS receiver: the truth carried to the fix's stamp by the car's motion, the
// antenna's position (a lever arm from base_link) with RTK noise, the sigma and fix type it
// reports, and its fault windows over (x, y, z). Framework-free: the gnss node turns a fix into a
// message.
#include "digest.hpp"
#include "faults.hpp"
#include "rng.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::sim {

// The fault windows a receiver takes, over (x, y, z).
inline const std::vector<std::string> kGnssFaultTypes = {"bias", "drift", "noise", "freeze", "dropout", "spikes", "sigma"};

// The truth a sensor samples: base_link's pose in the map frame and its body-frame motion.
struct BodyState {
  double x = 0, y = 0, z = 0, yaw = 0, pitch = 0, roll = 0;
  double vx = 0, vy = 0, yaw_rate = 0;
};

// The state dt seconds on, the car moving on at its velocity and yaw rate (dt: a few milliseconds).
BodyState carried(const BodyState& s, double dt);
// world_from_body (base_link): yaw, then pitch, then roll.
Eigen::Isometry3d world_from_body(const BodyState& s);

struct GnssNoise {
  double sigma_m = 0.015, sigma_z_m = 0.03;  // 1 sigma: horizontal, vertical
  double reported_sigma_m = -1;              // the sigma the receiver reports; < 0: sigma_m
  int fix_type = 3;                          // 0 none, 1 single, 2 float RTK, 3 fixed RTK
};

struct GnssFixValues {
  double x = 0, y = 0, z = 0, sigma_x = 0, sigma_y = 0, sigma_z = 0;
  int fix_type = 0;
  bool valid = false;
};

class GnssReceiver {
 public:
  // `antenna`: in base_link, m. The noise and spikes draw from `rng` (its seed: the run's).
  GnssReceiver(const Eigen::Vector3d& antenna, GnssNoise noise, FaultSchedule faults, Rng rng);

  enum class Epoch { dropped, frozen, fresh };
  // The epoch stamped stamp_ns from the truth stamped truth_stamp_ns: dropped (no fix), frozen
  // (the last fresh fix again) or fresh (in fix()). The fault windows are in seconds from
  // run_start_ns (the sim clock's zero; on the real clock, the run's start: sim/run_time.hpp).
  Epoch epoch(std::int64_t stamp_ns, const BodyState& truth, std::int64_t truth_stamp_ns, std::int64_t run_start_ns = 0);
  const GnssFixValues& fix() const { return fix_; }  // the last fresh fix

  std::uint64_t fixes() const { return fixes_; }  // fresh ones
  std::string digest() const { return digest_.hex(); }

 private:
  GnssFixValues measure(const BodyState& truth, const double (&n)[3], const FaultEffect& e) const;

  Eigen::Vector3d antenna_;
  double sigma_ = 0, sigma_z_ = 0, reported_ = 0;
  int fix_type_ = 3;
  FaultSchedule faults_;
  Rng rng_;
  GnssFixValues fix_;
  Digest digest_;
  std::uint64_t fixes_ = 0;
};

}  // namespace brickyard::sim
