#pragma once
// One estimator, framework-free: the pose filter, its update policy and the localization manager,
// fed in time order with IMU samples, rear-axle speeds and epochs of fixes. The plugin
// (fusion/plugin.cpp) only turns messages into these calls and the state into messages.
#include "localization_manager.hpp"
#include "map_witness.hpp"
#include "motion_check.hpp"
#include "reacquisition.hpp"
#include "update_selection.hpp"

#include <cmath>
#include <optional>
#include <vector>

namespace brickyard::estimation {

struct LocalizerParams {
  Policy policy = Policy::resilient;
  PolicyParams selection;
  FilterNoise noise;
  ManagerParams manager;                           // manager.receivers: 1 or 2
  // The antennas in base_link, m: the car's (the plugin takes them from the vehicle file).
  Eigen::Vector3d lever[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  double init_distance = 5;                        // m of travel before the heading is taken
  double roll_filter_s = 1;                        // s; 0: roll not used
  ReacquireParams reacquire;                       // resilient: coming back after a long outage
  // A second estimate of the pose (the scan mapper's, registered on its map): taken only while no
  // fix has been accepted for `scan_after_s` (GNSS degraded). With GNSS healthy it would count
  // the same information twice: the mapper starts from this filter's estimate as its prior.
  bool scan_pose = true;
  double scan_after_s = 0.3;                       // s without an accepted fix
  double scan_min_sigma = 0.05;                    // m: floor on the pose's reported spread
  double scan_gate = 13.8;                         // chi-square, 2 dof, 0.999: a pose farther is refused
  // The scan pose as an independent witness (a prior map's localizer, map_witness.hpp): judged on
  // every pose, GNSS healthy or not; once verified it refuses fixes that disagree with it, and a
  // map that never verified is not used.
  WitnessParams witness;
  // With the map witness: receivers whose fixes move unlike the car (motion_check.hpp) are caught
  // while the map stands, and the filter put where the car's own motion says it is.
  MotionParams motion;
};

class Localizer {
 public:
  explicit Localizer(LocalizerParams p);

  // An IMU sample at time t: the filter moves to t, then takes its yaw rate; the roll for the
  // lever arm follows the lateral specific force.
  // A sample with a value that is not finite (a broken or forged sender) is dropped and counted
  // (malformed()), here and in speed(), fixes() and scan_pose(): one receiver's NaN must not cost
  // the filter the other receiver's good fix, nor poison the state.
  void imu(double t, double gyro_z, double accel_y);
  // The rear axle's speed (mean of the rear wheels), used from the next prediction on.
  void speed(double v) {
    if (std::isfinite(v)) speed_ = v;
    else ++malformed_;
  }
  // One epoch of fixes stamped t (receiver ids 0 .. receivers - 1), each fix at its own stamp
  // when it has one (Fix::stamp; EpochGather). A fix stamped before the filter's time (delivered
  // late) is carried to now by dead reckoning's motion since its stamp; one older than that
  // history (about 1.5 s) is dropped (too_late()).
  void fixes(double t, const std::vector<Fix>& epoch);
  // A pose of base_link from another estimator (the scan mapper, the map localizer), stamped
  // `stamp` (earlier than now: a LiDAR frame arrives a sweep late and takes its registration's
  // time): moved to now by dead reckoning's motion since the stamp, judged by the map witness
  // when it is one (LocalizerParams::witness), then a position update when GNSS is degraded and,
  // as a witness, verified (see LocalizerParams::scan_pose). Returns whether it was taken.
  bool scan_pose(double stamp, const Eigen::Vector2d& xy, const Eigen::Matrix2d& cov);
  // A frame the scan pose's source could not locate (the map witness counts it).
  void scan_unlocated();
  // The manager's status at t (WARNING while the heading is not known yet).
  Status status(double t);
  // The filter's time: the stamp of the newest sample it has taken, s.
  double time() const { return t_; }
  // The pose at t: the filter's, carried from its time by its speed and yaw rate (a constant turn)
  // for at most max_s. On the real clock an estimator steps when an IMU sample arrives, and one
  // that arrived late (its sender stalled) leaves the filter behind the step's time: published
  // as now, its pose was that many metres behind the car (1.4 m at 77 m/s for 18 ms).
  struct Pose {
    double x = 0, y = 0, yaw = 0;
    double carried_s = 0;  // how far it was carried
    double short_s = 0;    // how far short of t it is (past max_s)
  };
  Pose pose_at(double t, double max_s) const;

  const PoseFilter& filter() const { return filter_; }
  const LocalizationManager& manager() const { return manager_; }
  const MapWitness& witness() const { return witness_; }
  const MotionCheck& motion() const { return motion_; }
  std::uint64_t motion_catches() const { return motion_catches_; }  // epochs a receiver was caught moving unlike the car
  double first_motion_catch_s() const { return first_motion_catch_s_; }  // -1: never
  const LocalizerParams& params() const { return p_; }
  // What happened since the last take_epoch_summary(): the last epoch's case and Δ per receiver
  // (-1: no fix), then reset to "predict only".
  std::pair<UpdateCase, std::vector<double>> take_epoch_summary();

  std::uint64_t epochs() const { return epochs_; }
  std::uint64_t rejected() const { return rejected_; }
  std::uint64_t epochs_of(UpdateCase c) const { return cases_[static_cast<int>(c)]; }
  std::uint64_t reacquisitions() const { return reacquisitions_; }
  std::uint64_t scan_updates() const { return scan_updates_; }
  std::uint64_t scan_refused() const { return scan_refused_; }
  std::uint64_t scan_unverified() const { return scan_unverified_; }  // not taken: the map never verified
  std::uint64_t malformed() const { return malformed_; }
  std::uint64_t late() const { return late_; }          // fixes carried to now
  std::uint64_t too_late() const { return too_late_; }  // fixes dropped: older than the history
  double late_max_s() const { return late_max_s_; }     // the latest of the carried ones

 private:
  void advance(double t);
  // dr_ moved by dt of the control input, the lateral velocity the filter's sideslip gain gives.
  void reckon_with_sideslip(double dt);
  // The wheel speed's scale the motion check learnt, where it is sure the wheels are off
  // (MotionCheck::wheel_scale; 1 otherwise): the filter's prediction takes the speed times it, so
  // that through an outage the car dead reckons on the wheels as GNSS measured them (a tyre's
  // radius off by 0.5 % is 0.4 m/s at 80 m/s).
  double wheel_scale() const;
  void initialize(double t, const std::vector<Fix>& epoch);
  // The car's motion from `stamp` to now by dead reckoning, laid on the filter's pose now: where a
  // point fixed to the car then is now. Nothing when the stamp is older than the history or ahead.
  struct Motion {
    Eigen::Vector2d then;  // the filter's position at the stamp, as dead reckoning puts it
    double turn = 0;       // rad turned since
    Eigen::Vector2d carry(const Eigen::Vector2d& p, const Eigen::Vector2d& now) const;
  };
  std::optional<Motion> motion_since(double stamp) const;
  void reacquire(double t, const std::vector<Fix>& epoch, EpochResult& r);
  // The epoch's fixes that the map witness refuses (all false without a standing map).
  std::vector<bool> refused_by_map(const std::vector<Fix>& epoch);
  // A fix within the gate of one refused for being off (`off`) is refused too, its receiver
  // caught (MapWitness::refuse_beside).
  void refuse_beside(const std::vector<Fix>& epoch, const std::vector<bool>& off, std::vector<bool>& refused);
  // apply_fixes on the fixes not refused; the refused ones rejected, at their distance.
  EpochResult apply_judged(const std::vector<Fix>& epoch, const std::vector<bool>& refused);
  bool gnss_accepted() const { return t_ - last_accepted_t_ < p_.scan_after_s; }
  // The map witness overrules the fixes: the filter relocated onto the map's position (`offset`
  // from the filter's, covariance `map_cov`).
  void overrule_fixes(const Eigen::Vector2d& offset, const Eigen::Matrix2d& map_cov);
  // A receiver caught lying this epoch: the filter moved onto the map's position (relocate).
  void relocate_on_catch();
  // Each fix's travel over the motion check's window against the car's (none judged without the
  // map witness).
  std::vector<MotionVerdict> judge_motion(const std::vector<Fix>& epoch);
  // Fixes not yet refused that moved unlike the car are refused and their receivers caught, while
  // the map stands (a witness to race on); with them, any fix beside them. Returns the verdict
  // that caught one, if any.
  const MotionVerdict* catch_moving(const std::vector<Fix>& epoch, const std::vector<MotionVerdict>& moved, std::vector<bool>& refused);
  // Caught moving: the filter put where it was at the window's start plus the car's travel since.
  void relocate_by_motion(const MotionVerdict& v);
  // A healthy epoch's windows learnt (every fix taken, none caught); otherwise the pending ones
  // forgotten.
  void learn_motion(const std::vector<MotionVerdict>& moved, const EpochResult& r);

  LocalizerParams p_;
  PoseFilter filter_;
  LocalizationManager manager_;
  std::optional<Eigen::Vector2d> first_;
  double t_ = -1, speed_ = 0, yaw_rate_ = 0, sin_roll_ = 0, roll_t_ = -1;
  bool have_imu_ = false;
  UpdateCase last_case_ = UpdateCase::predict_only;
  std::vector<double> last_delta_;
  std::uint64_t malformed_ = 0, late_ = 0, too_late_ = 0;
  double late_max_s_ = 0;
  std::uint64_t epochs_ = 0, rejected_ = 0, cases_[5] = {0, 0, 0, 0, 0}, reacquisitions_ = 0;
  Reacquisition reacquisition_;
  // Dead reckoning's pose (speed and yaw rate integrated, never corrected; yaw not wrapped) now
  // and after each prediction, for a late fix's or pose's stamp (about 1.5 s).
  struct Past {
    double t = 0, x = 0, y = 0, yaw = 0;
  };
  Past odo_;
  std::vector<Past> past_;
  std::size_t past_next_ = 0;
  double last_accepted_t_ = -1e300;
  std::uint64_t scan_updates_ = 0, scan_refused_ = 0, scan_unverified_ = 0;
  MapWitness witness_;
  MotionCheck motion_;
  // Dead reckoning with the filter's sideslip gain, never corrected: the motion check's travel.
  Past dr_;
  std::uint64_t motion_catches_ = 0;
  double first_motion_catch_s_ = -1;
};

}  // namespace brickyard::estimation
