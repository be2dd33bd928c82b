#include "estimator_report.hpp"

namespace brickyard::estimation {

ModeDue ModeCadence::step(double now, Status s) {
  if (last_step_ >= 0) time_in_[static_cast<int>(s)] += now - last_step_;
  last_step_ = now;
  ModeDue due;
  if (s != last_status_ || now - last_mode_ >= 0.1 - 1e-9) {
    due.publish = true;
    due.seq = seq_++;
    due.announce = s != last_status_ || seq_ == 1;
    last_mode_ = now;
    last_status_ = s;
  }
  return due;
}

std::vector<std::pair<std::string, double>> summary_metrics(const Localizer& loc, const ModeCadence& modes, Policy policy,
                                                            bool scan_pose_wired, const PolicyParams& selection) {
  std::vector<std::pair<std::string, double>> m = {
      {"epochs", static_cast<double>(loc.epochs())},
      {"fixes_rejected", static_cast<double>(loc.rejected())},
      {"malformed_samples", static_cast<double>(loc.malformed())},
      {"fixes_late", static_cast<double>(loc.late())},
      {"fixes_too_late", static_cast<double>(loc.too_late())},
      {"fix_late_max_s", loc.late_max_s()},
      {"epochs_single", static_cast<double>(loc.epochs_of(UpdateCase::single))},
      {"epochs_weighted", static_cast<double>(loc.epochs_of(UpdateCase::weighted))},
      {"epochs_partial", static_cast<double>(loc.epochs_of(UpdateCase::partial))},
      {"epochs_rejected", static_cast<double>(loc.epochs_of(UpdateCase::rejected))},
      {"time_warning_s", modes.time_in(Status::warning)},
      {"time_emergency_s", modes.time_in(Status::emergency)},
  };
  if (policy == Policy::resilient) m.emplace_back("reacquisitions", static_cast<double>(loc.reacquisitions()));
  if (scan_pose_wired) {
    m.emplace_back("scan_updates", static_cast<double>(loc.scan_updates()));
    m.emplace_back("scan_refused", static_cast<double>(loc.scan_refused()));
  }
  if (scan_pose_wired && loc.params().witness.enabled) {
    const MapWitness& w = loc.witness();
    m.emplace_back("map_verified", w.ever_verified() ? 1.0 : 0.0);
    m.emplace_back("map_mismatch", w.mismatch() ? 1.0 : 0.0);
    m.emplace_back("map_poses_unverified", static_cast<double>(loc.scan_unverified()));
    m.emplace_back("map_disagreements", static_cast<double>(w.disagreements()));
    m.emplace_back("map_jumps", static_cast<double>(w.jumps()));
    m.emplace_back("fixes_refused_by_map", static_cast<double>(w.refusals()));
    m.emplace_back("map_refusal_stretches", static_cast<double>(w.refusal_stretches()));
    m.emplace_back("map_first_refusal_s", w.first_refusal_s());
    m.emplace_back("map_overrulings", static_cast<double>(w.overrulings()));
    m.emplace_back("map_first_overrule_s", w.first_overrule_s());
    // The motion check (motion_check.hpp): what it learnt of the wheels, its largest judged
    // distance (a clean run's margin to the gate), and the epochs it caught a receiver.
    const MotionCheck& mc = loc.motion();
    m.emplace_back("motion_catches", static_cast<double>(loc.motion_catches()));
    m.emplace_back("motion_first_catch_s", loc.first_motion_catch_s());
    m.emplace_back("motion_scale", mc.scale());
    m.emplace_back("motion_wheel_scale", mc.wheel_scale());  // the scale dead reckoning took
    m.emplace_back("motion_spread_along", mc.spread_along());
    m.emplace_back("motion_spread_across", mc.spread_across());
    m.emplace_back("motion_max_d2", mc.max_d2());
  }
  if (policy == Policy::resilient) {
    m.emplace_back("epsilon_m", selection.epsilon);
    m.emplace_back("delta_m", selection.delta);
  }
  return m;
}

}  // namespace brickyard::estimation
