#pragma once
// The prior map as a third witness of the position, beside the two receivers. Framework-free.
// Receivers wrong together by the same offset agree with each other and, once the filter has
// followed them, with the prediction: the paper's selection cannot tell them (docs/algorithms.md).
// A pose registered on a map of the track is independent of GNSS, so it can. The rule:
//   verified   the map's poses have agreed with the filter for verify_s on end, while fixes were
//              being accepted or the filter was sure of its position to verify_sigma (dead
//              reckoning a few seconds into an outage: independent of the map, whose poses an
//              unverified map does not give it): the map is the track's and registers;
//   mismatch   not verified within mismatch_s of frames with GNSS accepted: a map of another
//              track (or one that does not register). Latched: a map of elsewhere may still
//              "locate" a few frames near the estimate where it happens to have structure, and
//              must not be trusted for them later in the run;
//   jump       a pose whose offset from the filter moved since the previous pose (within
//              fresh_s) by more than the gate on both poses' covariances: the registration
//              slipped (a wrong minimum), or the filter jumped; either way the map is not trusted
//              until it verifies again (jitter along a direction the frame barely tells is in
//              the covariance, and is no jump);
//   standing   verified, and its latest pose within fresh_s: a fix farther from the map's position
//              than the gate (chi-square 2 dof on both spreads, the map's floored at sigma_floor
//              in every direction) is refused, whatever the receiver claims (an RTK fix that lies),
//              provided the map's latest pose agreed with the filter: the fixes left the filter
//              and the map together (a step), not the map the fixes and the filter (a registration
//              confidently 2 m off, seen on Hockenheim's outer-wall map; the map pose is then the
//              odd one out and refuses nothing). No reacquisition may take the fixes' position
//              meanwhile. What the map cannot tell (a straight between parallel walls) is in its
//              covariance, so it refuses nothing along it.
//   caught     a receiver whose fix the standing map refused, or every receiver when the map
//              overruled the filter they had pulled: its fixes are refused from then on, map
//              standing or not, until they have agreed with the filter (its own spread, the floor)
//              for retrust_s on end. A drift caught across the road keeps drifting where the map
//              sees less (along a straight, a turn with one wall far off): judged by the map's
//              spread alone, its fixes would be let in again there and pull the filter, and the map
//              (guessing each frame from the filter) would follow. Released when the map has not
//              stood for hold_reacquire_s: with no witness left, the paper's rules judge them.
//              A fix that agrees with a refused one of the same epoch is refused and its receiver
//              caught too: receivers drifting together cross the gate a few epochs apart, and the
//              one still inside would pull the filter meanwhile.
//   overrule   verified and continuous (no jump), its poses have disagreed with the filter for
//              overrule_s on end: the fixes drifted and took the filter along (both receivers
//              pulled off together, slowly: multipath), which agreement alone cannot tell, since
//              the filter follows them; or, GNSS out, dead reckoning drifted past what the filter
//              believes and it refuses the map's poses. The filter is moved onto the map's
//              position (PoseFilter::relocate, as on a catch); the map then agrees with it and
//              stands, and refuses the drifting fixes.
// The map's position now is its latest pose's offset from the filter laid on the filter's position
// now: between two frames the filter only predicts, or takes fixes that agree with the map.
#include <Eigen/Core>

#include <cstdint>
#include <vector>

namespace brickyard::estimation {

struct WitnessParams {
  bool enabled = false;      // the scan pose is a prior map's (independent of GNSS)
  double fresh_s = 0.3;      // s: an older map pose witnesses nothing
  double sigma_floor = 0.5;  // m: floor on the map pose's spread in every direction when judging
  double gate = 13.8;        // chi-square, 2 dof, 0.999
  double verify_s = 2.0;     // s of agreement with the filter before the map is trusted
  double verify_sigma = 1.0; // m: without accepted fixes, agreement counts only with the filter this sure
  double hold_reacquire_s = 5.0;  // s after the map last stood: no reacquisition
  double mismatch_s = 10.0;  // s of map poses with GNSS accepted, never verified: not this track's map
  double overrule_s = 1.0;   // s a verified map disagrees with the filter before the filter is put on it (0: never)
  double retrust_s = 3.0;    // s a caught receiver's fixes agree with the filter before they are taken again (0: never caught)
};

// A covariance whose spread in every direction is at least `sigma`: its eigenvalues floored. (A
// floor on the diagonal alone leaves a pose long along a diagonal direction sure to nothing
// across it: 100 m along a straight at 45 degrees has a near-zero eigenvalue across.)
Eigen::Matrix2d with_floor(const Eigen::Matrix2d& cov, double sigma);

// One map pose carried to now, and how it stands against the filter there.
struct MapPoseNow {
  double t = 0;
  Eigen::Vector2d offset;   // the map's position less the filter's, m
  Eigen::Matrix2d cov;      // the map pose's covariance, floored
  Eigen::Matrix2d innovation_cov;  // the filter's position covariance plus cov
};

class MapWitness {
 public:
  explicit MapWitness(WitnessParams p) : p_(p) {}
  // A map pose at t; `gnss_accepted`: a fix has been accepted lately (GNSS healthy).
  void observe(const MapPoseNow& pose, bool gnss_accepted);
  // A frame the map localizer could not locate, at t.
  void unlocated(double t, bool gnss_accepted);
  bool verified() const { return verified_; }
  bool agrees() const { return agrees_; }  // the latest pose agreed with the filter
  bool standing(double t) const { return verified_ && last_t_ >= 0 && t - last_t_ <= p_.fresh_s; }
  // Standing, or was within hold_reacquire_s: the fixes' position is not taken by reacquisition
  // (a map that slipped for a frame during a bias must not let the biased fixes in meanwhile).
  bool holds_reacquisition(double t) const { return standing(t) || t - last_verified_t_ <= p_.hold_reacquire_s; }
  // Whether a fix of `receiver` (its base_link position, covariance R) is refused at t, given the
  // filter's position now and its spread: by the standing map, or because the receiver is caught.
  // Counted.
  bool refuses(double t, const Eigen::Vector2d& base, const Eigen::Matrix2d& R, const Eigen::Vector2d& filter_xy, int receiver = 0,
               const Eigen::Matrix2d& filter_cov = Eigen::Matrix2d::Zero());
  // A fix refused with the one of `receiver` beside it: it agrees with a receiver the map caught
  // (receivers wrong together drift together, one a little past the gate, the other not yet).
  // Counted, and the receiver caught.
  void refuse_beside(double t, int receiver);
  // Whether the latest refusal was of a fix off where it should be (off the map, or a caught
  // receiver's off the filter), not of one already agreeing that waits out retrust_s: only those
  // make the fixes beside them suspect (two receivers back at the truth would otherwise keep each
  // other caught).
  bool refused_off() const { return refused_off_; }
  bool any_caught() const {
    for (const auto& c : caught_)
      if (c.caught) return true;
    return false;
  }
  // The latest pose's offset from the filter, and its covariance (floored).
  const Eigen::Vector2d& offset() const { return offset_; }
  const Eigen::Matrix2d& cov() const { return cov_; }
  // The filter moved by `shift` towards the map (the offset less by it), not overruling it.
  void shifted(const Eigen::Vector2d& shift) { offset_ -= shift; }
  bool caught(int receiver) const { return receiver >= 0 && receiver < static_cast<int>(caught_.size()) && caught_[receiver].caught; }
  // Not verified within mismatch_s of frames with GNSS accepted (none located, or located off
  // the fixes): a map of another track, or one that does not register. Latched.
  bool mismatch() const { return mismatch_; }
  // Standing, and has disagreed with the filter for overrule_s on end, no jump since it
  // verified: the filter drifted (with the fixes, or on dead reckoning).
  bool overrules(double t) const {
    return p_.overrule_s > 0 && standing(t) && disagree_since_ >= 0 && t - disagree_since_ >= p_.overrule_s;
  }
  // The filter moved by `shift` onto the map's position at t: the latest offset from it is
  // less by that (no jump), and it agrees.
  void relocated(double t, const Eigen::Vector2d& shift);
  Eigen::Matrix2d floored(const Eigen::Matrix2d& cov) const { return with_floor(cov, p_.sigma_floor); }

  bool ever_verified() const { return ever_verified_; }
  std::uint64_t refusals() const { return refusals_; }
  std::uint64_t refusal_stretches() const { return stretches_; }
  double first_refusal_s() const { return first_refusal_; }
  double last_refusal_s() const { return last_refusal_; }  // -1e300: never
  std::uint64_t disagreements() const { return disagreements_; }  // poses off accepted GNSS
  std::uint64_t jumps() const { return jumps_; }
  std::uint64_t overrulings() const { return overrulings_; }
  double first_overrule_s() const { return first_overrule_; }  // -1: never

 private:
  // The time since the previous frame, located or not (0 after a gap), counted towards mismatch.
  void count_frame(double t, bool gnss_accepted);
  struct Caught {
    bool caught = false;
    double agree_since = -1;
  };
  Caught& entry(int receiver);  // the receiver's, made when first asked (a negative id is 0's)
  // A caught receiver's fix: still refused, or the agreement that releases it counted.
  bool still_caught(double t, Caught& c, const Eigen::Vector2d& base, const Eigen::Matrix2d& R, const Eigen::Vector2d& filter_xy,
                    const Eigen::Matrix2d& filter_cov);
  void count_refusal(double t);

  WitnessParams p_;
  bool verified_ = false, ever_verified_ = false, mismatch_ = false, agrees_ = false;
  double last_t_ = -1, agree_since_ = -1, last_frame_t_ = -1, unverified_s_ = 0, last_verified_t_ = -1e300;
  double disagree_since_ = -1, first_overrule_ = -1;
  Eigen::Vector2d offset_ = Eigen::Vector2d::Zero();
  Eigen::Matrix2d cov_ = Eigen::Matrix2d::Identity();
  std::uint64_t refusals_ = 0, stretches_ = 0, disagreements_ = 0, jumps_ = 0, overrulings_ = 0;
  double first_refusal_ = -1, last_refusal_ = -1e300;
  std::vector<Caught> caught_;  // by receiver
  bool refused_off_ = false;
};

}  // namespace brickyard::estimation
