#include "race_judge.hpp"

#include <cstdio>

namespace brickyard::sim {

namespace {

using Kind = RefereeNotice::Kind;

// A line as the referee prints it: into a buffer of N characters (a longer one is cut there).
template <std::size_t N = 160, class... A> std::string printed(const char* format, A... args) {
  char buf[N];
  std::snprintf(buf, sizeof buf, format, args...);
  return buf;
}

RefereeNotice notice(Kind kind, std::string text, std::string field = {}) { return {kind, std::move(text), std::move(field)}; }

}  // namespace

RaceJudge::RaceJudge(const Track& track, Footprint fp, RaceRules rules)
    : ref_(track, fp), rules_(rules), fp_(fp), order_(track, fp.front + fp.rear) {}

std::vector<RefereeNotice> RaceJudge::update(const TruthSample& s) {
  std::vector<RefereeNotice> out;
  last_ = s;
  const Referee::Events ev = ref_.update(s);
  if (++samples_ % 100 == 0 || ev.lap_completed) progress(s, out);  // the progress line: a few times a second of sim time
  if (ev.lap_completed) lap_completed(out);
  if (ev.track_violation) out.push_back(notice(Kind::warn, printed("track limits: car left the track at s = %.1f m", ref_.s())));
  if (ev.obstacle_hit) out.push_back(notice(Kind::warn, printed("obstacle hit at s = %.1f m", ref_.s())));
  check_failures(s, ev, out);
  return out;
}

std::vector<RefereeNotice> RaceJudge::run_ended() {
  std::vector<RefereeNotice> out;
  // A race that ended before its laps did not do its job, however it ended (duration, a stop).
  // (Once: a race this referee has already failed — a crash, a stop — says so once.)
  if (rules_.laps > 0 && ref_.laps_completed() < rules_.laps && !failed_)
    fail(printed<200>("did not finish: %d of %lld laps; the run ended at t = %.1f s with the car at s = %.1f m",
                      ref_.laps_completed(), static_cast<long long>(rules_.laps), ref_.t(), ref_.s()),
         out);
  return out;
}

std::optional<std::string> RaceJudge::world_never_seen(std::int64_t laps) {
  if (laps > 0) return "did not finish: 0 of " + std::to_string(laps) + " laps; the referee never saw the world";
  return std::nullopt;
}

void RaceJudge::progress(const TruthSample& s, std::vector<RefereeNotice>& out) const {
  out.push_back(notice(Kind::status, printed("%.1f m/s", s.speed), "speed"));
  out.push_back(notice(Kind::status,
                       printed("%d%s", ref_.laps_completed() + 1, rules_.laps > 0 ? ("/" + std::to_string(rules_.laps)).c_str() : ""),
                       "lap"));
}

void RaceJudge::lap_completed(std::vector<RefereeNotice>& out) const {
  out.push_back(notice(Kind::info, printed("lap %d: %.3f s", ref_.laps_completed(), ref_.lap_times().back())));
  if (rules_.laps > 0 && ref_.laps_completed() >= rules_.laps)
    out.push_back(notice(Kind::finish, std::to_string(rules_.laps) + " laps completed"));
}

void RaceJudge::check_failures(const TruthSample& s, const Referee::Events& ev, std::vector<RefereeNotice>& out) {
  const double clearance_required = rules_.obstacle_clearance_required;
  if (clearance_required >= 0 && ref_.obstacle_min_clearance() < clearance_required) {
    rules_.obstacle_clearance_required = -1;  // once
    fail(printed("obstacle passed %.2f m off at s = %.1f m (at least %.2f m required)", ref_.obstacle_min_clearance(), ref_.s(),
                 clearance_required),
         out);
  }
  if (rules_.laps > 0 && rules_.stopped_timeout_s > 0 && !failed_ && ref_.stopped_for() >= rules_.stopped_timeout_s)
    fail(printed("did not finish: %d of %lld laps; the car stopped at s = %.1f m and stood %.1f s", ref_.laps_completed(),
                 static_cast<long long>(rules_.laps), ref_.s(), ref_.stopped_for()),
         out);
  if (ev.wall_contact) {
    const std::string line = printed("wall contact at s = %.1f m, t = %.3f s, %.1f m/s", ref_.s(), s.t, s.speed);
    if (rules_.crash_ends_run) fail("crash: " + line, out);
    else out.push_back(notice(Kind::warn, line));
  }
}

std::vector<RefereeNotice> RaceJudge::other_cars(const std::vector<std::optional<CarBox>>& others) {
  std::vector<RefereeNotice> out;
  if (samples_ == 0) return out;
  // A car that overlaps ours the first time it is seen was placed inside it: its start is wrong.
  const CarBox ours{last_.x, last_.y, last_.yaw, fp_};
  if (seen_.size() < others.size()) seen_.resize(others.size(), false);
  for (std::size_t k = 0; k < others.size(); ++k) {
    if (!others[k] || seen_[k]) continue;
    seen_[k] = true;
    if (cars_touch(ours, *others[k]) && !failed_)
      fail(printed("car %d starts inside ours at t = %.3f s (s = %.1f m): its start_s and start_d place it there", static_cast<int>(k), last_.t,
                   ref_.s()),
           out);
  }
  if (failed_) return out;
  for (int k : cars_.update(ours, others)) {
    const std::string line = printed("contact with car %d at s = %.1f m, t = %.3f s, %.1f m/s", k, ref_.s(), last_.t, last_.speed);
    if (rules_.crash_ends_run && !failed_) fail("crash: " + line, out);
    else out.push_back(notice(Kind::warn, line));
  }
  for (const RaceOrder::Pass& p : order_.update(last_.t, ours, others))
    out.push_back(notice(Kind::info, printed(p.ours ? "passed car %d at s = %.1f m, t = %.3f s" : "passed by car %d at s = %.1f m, t = %.3f s",
                                             p.car, p.s, p.t)));
  return out;
}

void RaceJudge::fail(std::string why, std::vector<RefereeNotice>& out) {
  failed_ = true;
  out.push_back(notice(Kind::fail, std::move(why)));
}

}  // namespace brickyard::sim
