#pragma once
// The parameters of the three estimators (plugin.cpp): the common ones, then their policy's, and
// where the antennas sit. Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "estimation/common/localizer.hpp"
#include "vehicle_param.hpp"

#include <string>
#include <vector>

namespace brickyard::estimation {

// What the graph says: the car's file and where on it the antennas sit, and the filter's own
// parameters.
struct Settings {
  std::string vehicle = plugins::default_vehicle_file;
  std::vector<double> antenna0, antenna1;  // empty: the mount's place in the vehicle file
  std::string antenna0_mount = "gnss_left", antenna1_mount = "gnss_right";
  double epoch_pair_s = 0.01, epoch_wait_s = 0.05;
  double carry_max_s = 0.1;
  LocalizerParams loc;
};

// The map witness's parameters (map_witness.hpp; docs/algorithms.md).
inline void bind_witness(ParamBinding<Settings>& b) {
  using L = LocalizerParams;
  using W = WitnessParams;
  b.bind("scan_pose_witness", &Settings::loc, &L::witness, &W::enabled)
      .doc("scan_pose is an independent witness (a prior map's localizer, not the scan mapper): once its poses have agreed with "
           "accepted fixes for witness_verify_s, fixes that disagree with it are refused (receivers wrong together); a map that "
           "never verifies is not used (docs/algorithms.md)");
  b.bind("witness_verify_s", &Settings::loc, &L::witness, &W::verify_s).in_unit("s").range(0, 3600)
      .doc("the map's poses agree with the filter this long (fixes accepted, or the filter sure to witness_verify_sigma) before it may refuse a fix");
  b.bind("witness_sigma_floor", &Settings::loc, &L::witness, &W::sigma_floor).in_unit("m").range(0.01, 100)
      .doc("floor on the map pose's spread in every direction when judging fixes");
  b.bind("witness_verify_sigma", &Settings::loc, &L::witness, &W::verify_sigma).in_unit("m").range(0.01, 1000)
      .doc("without accepted fixes, the map's agreement counts towards verifying it only with the filter's position this sure");
  b.bind("witness_mismatch_s", &Settings::loc, &L::witness, &W::mismatch_s).in_unit("s").range(0.1, 3600)
      .doc("frames with GNSS accepted and the map never verified this long: the map is not this track's (reported)");
  b.bind("witness_overrule_s", &Settings::loc, &L::witness, &W::overrule_s).in_unit("s").range(0, 3600)
      .doc("a verified map that disagrees this long with the filter overrules it: the filter is put on the map "
           "(both receivers drifting together, or dead reckoning drifted in an outage); 0: never");
  b.bind("witness_retrust_s", &Settings::loc, &L::witness, &W::retrust_s).in_unit("s").range(0, 3600)
      .doc("a receiver the map caught (a fix refused, or the filter it pulled overruled) stays refused until its fixes have "
           "agreed with the filter this long; 0: judged fix by fix");
  using C = MotionParams;
  b.bind("motion_window_s", &Settings::loc, &L::motion, &C::window_s).in_unit("s").range(0, 60)
      .doc("with the map witness: each receiver's travel over this long against the car's predicted travel; a receiver moving "
           "unlike the car is caught while the map stands (receivers drifting together); 0: no check (docs/algorithms.md)");
  b.bind("motion_gate", &Settings::loc, &L::motion, &C::gate).range(1, 1000).doc("chi-square, 1 dof, of the motion check: the fixes' travel along the car's against it");
  b.bind("motion_learn_s", &Settings::loc, &L::motion, &C::learn_s).in_unit("s").range(0, 3600)
      .doc("s of healthy travel learnt (the wheels' scale, the spreads) before the motion check judges");
  b.bind("motion_spread_floor", &Settings::loc, &L::motion, &C::spread_floor).range(1e-6, 1)
      .doc("floor on the motion check's learnt relative spreads");
}

// The three estimators' parameters: the common ones, then their policy's.
template <Policy P> ParamBinding<Settings> bindings() {
  using L = LocalizerParams;
  using N = FilterNoise;
  using M = ManagerParams;
  using S = PolicyParams;
  Settings defaults;
  defaults.loc.policy = P;
  ParamBinding<Settings> b(defaults);
  plugins::bind_vehicle(b, &Settings::vehicle).doc("the car's description file: where its GNSS antennas sit");
  b.bind("antenna0", &Settings::antenna0).in_unit("m").range(-100, 100).doc("first receiver's antenna in base_link, m (x, y, z); empty: antenna0_mount's");
  b.bind("antenna1", &Settings::antenna1).in_unit("m").range(-100, 100).doc("second receiver's antenna in base_link, m (x, y, z); empty: antenna1_mount's");
  b.bind("antenna0_mount", &Settings::antenna0_mount).doc("the first receiver's mount in the vehicle file");
  b.bind("antenna1_mount", &Settings::antenna1_mount).doc("the second receiver's mount in the vehicle file");
  b.bind("roll_filter_s", &Settings::loc, &L::roll_filter_s).in_unit("s").range(0, 3600).doc("time constant of the roll taken from the IMU; 0: roll not used");
  b.bind("speed_sigma", &Settings::loc, &L::noise, &N::speed).in_unit("m/s").range(0, 100)
      .doc("wheel speed input noise");
  b.bind("gyro_sigma", &Settings::loc, &L::noise, &N::yaw_rate).in_unit("rad/s").range(0, 10).doc("yaw rate input noise");
  b.bind("process_position", &Settings::loc, &L::noise, &N::position).in_unit("m/sqrt(s)").range(0, 100);
  b.bind("process_yaw", &Settings::loc, &L::noise, &N::yaw).in_unit("rad/sqrt(s)").range(0, 10);
  b.bind("process_slip_gain", &Settings::loc, &L::noise, &N::slip_gain).in_unit("s^2/m/sqrt(s)").range(0, 10);
  b.bind("scan_pose", &Settings::loc, &L::scan_pose)
      .doc("with scan_pose wired: its registered poses are position updates while no fix has been accepted for scan_after_s (docs/mapping.md)");
  b.bind("scan_after_s", &Settings::loc, &L::scan_after_s).in_unit("s").range(0, 3600).doc("GNSS degraded: no fix accepted for this long");
  b.bind("scan_pose_trusted_s", &Settings::loc, &L::manager, &M::witness_timeout_s).in_unit("s").range(0, 60)
      .doc("a scan pose taken within this long keeps the status at WARNING (the car on its path) while every receiver is lost: "
           "for an independent witness, the map localizer's (docs/algorithms.md); 0: EMERGENCY as without one");
  bind_witness(b);
  b.bind("scan_min_sigma", &Settings::loc, &L::scan_min_sigma).in_unit("m").range(0.001, 100).doc("floor on a scan pose's spread");
  b.bind("epoch_pair_s", &Settings::epoch_pair_s).in_unit("s").range(0, 1)
      .doc("real clock: two receivers' fixes stamped this close are one epoch (each carried from its own stamp)");
  b.bind("epoch_wait_s", &Settings::epoch_wait_s).in_unit("s").range(0, 1)
      .doc("real clock: how long a receiver's fix waits for the other receiver's of its epoch");
  b.bind("carry_max_s", &Settings::carry_max_s).in_unit("s").range(0, 1)
      .doc("an estimate is the pose at its step's time, carried there from the newest IMU sample's stamp by the filter's speed "
           "and yaw rate (a sample that arrived late) for at most this long; stamped where it got to");
  b.bind("init_distance", &Settings::loc, &L::init_distance).in_unit("m").range(0.5, 1000).doc("travel before the heading is taken from the fixes");
  b.bind("emergency_after_s", &Settings::loc, &L::manager, &M::emergency_after_s).in_unit("s").range(0, 3600)
      .doc("every receiver rejected or silent this long: EMERGENCY");
  b.bind("recover_after_s", &Settings::loc, &L::manager, &M::recover_after_s).in_unit("s").range(0, 3600)
      .doc("hysteresis: a level clears after this long without its cause");
  b.bind("fix_timeout_s", &Settings::loc, &L::manager, &M::fix_timeout_s).in_unit("s").range(0.01, 3600).doc("a receiver silent this long counts as rejected");
  if constexpr (P == Policy::resilient) {
    b.bind("epsilon_m", &Settings::loc, &L::selection, &S::epsilon).in_unit("m").range(0, 1000)
        .doc("every fix within this: all qualified (weighting paper: the closest one alone)");
    b.bind("delta_m", &Settings::loc, &L::selection, &S::delta).in_unit("m").range(0, 1000).doc("fixes beyond this are rejected");
    b.bind_choice("weighting", {{"likelihood", Weighting::likelihood}, {"paper", Weighting::paper}}, &Settings::loc, &L::selection, &S::weighting)
        .doc("weights: likelihood (exp(-max(0, d^2 - 9)/2), d Mahalanobis) or paper (1 - delta/sum); docs/algorithms.md");
    using R = ReacquireParams;
    b.bind("reacquire", &Settings::loc, &L::reacquire, &R::enabled)
        .doc("after an outage that left every fix beyond delta: take the fixes' position (and the heading the fit finds) again once the receivers agree with each other and with the motion model (docs/algorithms.md)");
    b.bind("reacquire_agree_m", &Settings::loc, &L::reacquire, &R::agree_m).in_unit("m").range(0.01, 100)
        .doc("the receivers' base_link positions within this of each other");
    b.bind("reacquire_motion_m", &Settings::loc, &L::reacquire, &R::motion_m).in_unit("m").range(0.01, 100)
        .doc("the dead-reckoned path, moved and turned onto the fixes' path, within this of it at every epoch of the window");
    b.bind("reacquire_max_turn", &Settings::loc, &L::reacquire, &R::max_turn).in_unit("rad").range(0, 3.14)
        .doc("the largest heading error the fit may correct");
    b.bind("reacquire_min_span_m", &Settings::loc, &L::reacquire, &R::min_span_m).in_unit("m").range(0.1, 1000)
        .doc("below this much travel in the window the turn cannot be told: taken as zero");
    b.bind("reacquire_window_s", &Settings::loc, &L::reacquire, &R::window_s).in_unit("s").range(0.05, 60)
        .doc("both held this long before the position is taken");
    b.not_above("epsilon_m", "delta_m");
  } else if constexpr (P == Policy::gated) {
    b.bind("gate_chi2", &Settings::loc, &L::selection, &S::gate_chi2).range(0, 1e6).doc("squared Mahalanobis threshold (2 dof; 13.8 = 99.9 %)");
  }
  return b;
}

// The antennas in base_link, m (`lever`: receiver 0's, 1's): the graph's numbers, or the vehicle
// file's mounts.
inline void place_antennas(Context& ctx, const Settings& set, Eigen::Vector3d (&lever)[2]) {
  const vehicle::Vehicle car = plugins::read_vehicle(ctx, set.vehicle);
  for (int r = 0; r < 2; ++r) {
    const std::string which = std::string("antenna") + char('0' + r);
    const auto a = plugins::sensor_place(car, set.vehicle, r == 0 ? set.antenna0_mount : set.antenna1_mount, which + "_mount",
                                         r == 0 ? set.antenna0 : set.antenna1, which);
    lever[r] = {a[0], a[1], a[2]};
  }
}

}  // namespace brickyard::estimation
