#include "sample_feed.hpp"

#include <algorithm>
#include <map>

namespace brickyard::estimation {

Fix Receivers::fix(int receiver_id, const Eigen::Vector2d& antenna, double sigma_x, double sigma_y) const {
  Fix f;
  f.receiver = receiver_id < 2 && count == 2 ? receiver_id : 0;
  f.antenna = antenna;
  f.lever = lever[f.receiver];
  f.sigma = std::max(sigma_x, sigma_y);
  return f;
}

void feed_in_time_order(Localizer& loc, EpochGather* gather, const std::vector<ImuSample>& imu, const std::vector<GnssSample>& gnss) {
  struct Event {
    const ImuSample* imu;
    const GnssSample* fix;
  };
  std::multimap<double, Event> events;  // one stamp's events in the order they were put in
  for (const ImuSample& m : imu) events.emplace(m.t, Event{&m, nullptr});
  for (const GnssSample& f : gnss) events.emplace(f.t, Event{nullptr, &f});
  std::vector<Fix> epoch;
  double epoch_t = -1, latest = -1;
  for (auto& [t, e] : events) {
    latest = std::max(latest, t);
    if (e.imu) {
      loc.fixes(epoch_t, epoch);
      epoch.clear();
      loc.imu(t, e.imu->gyro_z, e.imu->accel_y);
      continue;
    }
    if (!e.fix->valid) continue;
    if (gather) {  // the real clock: the epoch's other receiver may come in a later step
      gather->add(t, e.fix->fix);  // finite: the stamp is whole nanoseconds
      continue;
    }
    if (t != epoch_t) {
      loc.fixes(epoch_t, epoch);
      epoch.clear();
    }
    epoch_t = t;
    epoch.push_back(e.fix->fix);
  }
  loc.fixes(epoch_t, epoch);
  if (gather)
    for (auto& e : gather->release(latest)) loc.fixes(e.t, e.fixes);
}

void feed_scan_poses(Localizer& loc, const std::vector<ScanPoseSample>& poses) {
  for (const ScanPoseSample& s : poses)
    if (s.update_case == 2) loc.scan_pose(s.t, s.xy, s.cov);
    else loc.scan_unlocated();
}

}  // namespace brickyard::estimation
