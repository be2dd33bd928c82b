#pragma once
// The referee's rules over the Referee's figures: when a race is finished (its laps done) or the run
// failed (a crash, a pylon passed too near, a car standing short of its laps, a race cut short), and
// the progress fields and log lines that say so. Framework-free: it returns what to say in the
// order to say it, and the referee node passes that on.
#include "car_contacts.hpp"
#include "race_order.hpp"
#include "referee.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::sim {

struct RaceRules {
  bool crash_ends_run = true;  // a wall contact fails the run (else it is a warning)
  // A race requires a clearance to every pylon: a pass nearer than this, or a hit, fails the run
  // (negative: off).
  double obstacle_clearance_required = 0.5;
  std::int64_t laps = 0;          // a race of this many laps; 0: no race
  double stopped_timeout_s = 10;  // a car standing this long short of its laps fails the run; 0: off
};

// One thing the referee says: a progress field (status: `field` = `text`), a log line, or the
// run's end (finish, fail).
struct RefereeNotice {
  enum class Kind { status, info, warn, finish, fail };
  Kind kind = Kind::info;
  std::string text;
  std::string field;
};

class RaceJudge {
 public:
  RaceJudge(const Track& track, Footprint fp, RaceRules rules);

  // One ground-truth sample: what it makes the referee say.
  std::vector<RefereeNotice> update(const TruthSample& s);
  // The other cars' latest poses (none: not seen yet) against ours at the latest sample: a contact
  // fails the run as a wall's does (crash_ends_run), naming the car; a pass, either way, is said
  // (issue 46).
  std::vector<RefereeNotice> other_cars(const std::vector<std::optional<CarBox>>& others);
  const CarContactBook& car_contacts() const { return cars_; }
  const RaceOrder& order() const { return order_; }
  // The run is over: a race short of its laps did not finish (unless it failed already).
  std::vector<RefereeNotice> run_ended();
  // The run ended before the world came: a race did not finish. Nothing when there was no race.
  static std::optional<std::string> world_never_seen(std::int64_t laps);

  Referee& referee() { return ref_; }
  const Referee& referee() const { return ref_; }
  bool failed() const { return failed_; }

 private:
  void progress(const TruthSample& s, std::vector<RefereeNotice>& out) const;
  void lap_completed(std::vector<RefereeNotice>& out) const;
  void check_failures(const TruthSample& s, const Referee::Events& ev, std::vector<RefereeNotice>& out);
  void fail(std::string why, std::vector<RefereeNotice>& out);

  Referee ref_;
  RaceRules rules_;
  Footprint fp_;
  CarContactBook cars_;
  RaceOrder order_;
  std::vector<bool> seen_;  // per other car: seen once (a first sight inside ours is a wrong start)
  TruthSample last_;
  bool failed_ = false;  // the run has failed: one reason is enough
  std::uint64_t samples_ = 0;
};

}  // namespace brickyard::sim
