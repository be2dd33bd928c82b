// The system manager obeying race control (common/flag_gate.hpp): each transition of its state
// machine, what each state makes of the command, and a yellow and a red on a car that brakes as
// the vehicle file says (the AV-21: 815 kg, 20 000 N of brakes, 9 000 N of drive).
#include "control/common/flag_gate.hpp"

#include "av21.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard::control;
using brickyard::motion::Command;

namespace {

constexpr double kStopBrake = 6.0 * 815 / 20000;  // 0.2445: 6 m/s^2 by the brakes alone

FlagInput flags(double t, TrackFlag track, VehicleFlag vehicle = VehicleFlag::none, double target = 0, int lap = 0,
                bool heard = true) {
  return {t, heard, track, vehicle, target, lap};
}

const Command kRace{0.05, 0.8, 0.0, 70.0};  // the path tracker's: steer, throttle, brake, target

// Steps the gate at t and returns the transition.
FlagTransition at(FlagGate& g, double t) { return g.update(t); }

}  // namespace

TEST(FlagGate, WaitsHoldingTheCarUntilRaceControlIsHeard) {
  FlagGate g({}, kStopBrake);
  EXPECT_FALSE(at(g, 0.0).happened);
  EXPECT_EQ(g.state(), RaceState::waiting);
  const Command c = g.apply(kRace, 0.0);
  EXPECT_EQ(c.throttle, 0.0);
  EXPECT_DOUBLE_EQ(c.brake, kStopBrake);
  EXPECT_EQ(c.steer, kRace.steer);  // the stop steers along the path
  g.flags(flags(0.02, TrackFlag::none, VehicleFlag::none, 0, 0, false));  // the interface: nothing heard yet
  EXPECT_FALSE(at(g, 0.02).happened);
  g.flags(flags(0.1, TrackFlag::green));
  const FlagTransition tr = at(g, 0.1);
  ASSERT_TRUE(tr.happened);
  EXPECT_EQ(tr.from, RaceState::waiting);
  EXPECT_EQ(tr.to, RaceState::racing);
  EXPECT_EQ(flag_line(tr, 0.1), "race control: WAITING -> RACING at t = 0.100 s: track flag GREEN: racing");
  const Command r = g.apply(kRace, 0.1);
  EXPECT_EQ(r.throttle, kRace.throttle);
  EXPECT_EQ(r.brake, kRace.brake);
}

TEST(FlagGate, YellowCapsTheSpeedAtTheTargetAndGreenLiftsIt) {
  FlagGate g({}, kStopBrake);
  g.flags(flags(0, TrackFlag::green));
  at(g, 0);
  g.flags(flags(1, TrackFlag::yellow, VehicleFlag::none, 26.8224));  // 60 mph
  const FlagTransition tr = at(g, 1);
  EXPECT_EQ(tr.to, RaceState::caution);
  EXPECT_EQ(tr.reason, "track flag YELLOW: speed capped at 26.8 m/s");
  EXPECT_TRUE(g.capped());
  // No speed yet: a cap cannot be held, so the car stops.
  EXPECT_DOUBLE_EQ(g.apply(kRace, 1).brake, kStopBrake);
  // Far over the target: throttle off, the stop's brake at most.
  g.speed(1, 60);
  Command c = g.apply(kRace, 1);
  EXPECT_EQ(c.throttle, 0);
  EXPECT_DOUBLE_EQ(c.brake, kStopBrake);
  EXPECT_DOUBLE_EQ(c.target_speed, 26.8224);
  // Just over: the brake 0.5 x 0.2 m/s; just under: at most the throttle 0.5 x 0.4 m/s.
  g.speed(1.01, 27.0224);
  EXPECT_NEAR(g.apply(kRace, 1.01).brake, 0.1, 1e-9);
  g.speed(1.02, 26.4224);
  c = g.apply(kRace, 1.02);
  EXPECT_NEAR(c.throttle, 0.2, 1e-9);
  EXPECT_EQ(c.brake, 0.0);
  EXPECT_EQ(c.steer, kRace.steer);
  // A speed older than speed_timeout_s (0.2 s) is none: the car stops.
  EXPECT_DOUBLE_EQ(g.apply(kRace, 1.3).brake, kStopBrake);
  // Orange is a caution too; green lifts the cap.
  g.flags(flags(2, TrackFlag::orange, VehicleFlag::none, 20));
  EXPECT_FALSE(at(g, 2).happened);
  g.flags(flags(3, TrackFlag::green));
  EXPECT_EQ(at(g, 3).to, RaceState::racing);
  EXPECT_FALSE(g.capped());
  EXPECT_EQ(g.apply(kRace, 3).throttle, kRace.throttle);
}

TEST(FlagGate, RedAndTheCarFlagsThatStopBringAControlledStopUntilGreen) {
  for (const FlagInput& stop : {flags(1, TrackFlag::red), flags(1, TrackFlag::green, VehicleFlag::black),
                                flags(1, TrackFlag::green, VehicleFlag::purple), flags(1, TrackFlag::unknown),
                                flags(1, TrackFlag::none), flags(1, TrackFlag::green, VehicleFlag::unknown)}) {
    FlagGate g({}, kStopBrake);
    g.flags(flags(0, TrackFlag::green));
    at(g, 0);
    g.flags(stop);
    const FlagTransition tr = at(g, 1);
    EXPECT_EQ(tr.from, RaceState::racing);
    EXPECT_EQ(tr.to, RaceState::stopping) << track_flag_name(stop.track);
    const Command c = g.apply(kRace, 1);
    EXPECT_EQ(c.throttle, 0);
    EXPECT_DOUBLE_EQ(c.brake, kStopBrake);
    EXPECT_EQ(c.steer, kRace.steer);
    EXPECT_EQ(g.apply({0, 0, 1.0, 0}, 1).brake, 1.0);  // a harder brake (a safe stop) is kept
    g.flags(flags(5, TrackFlag::green));
    EXPECT_EQ(at(g, 5).to, RaceState::racing);
  }
  FlagGate g({}, kStopBrake);
  g.flags(flags(0, TrackFlag::red));
  const FlagTransition tr = at(g, 0);
  EXPECT_EQ(tr.to, RaceState::stopping);
  EXPECT_EQ(tr.reason, "track flag RED, vehicle flag NONE: a controlled stop at 6 m/s^2");
}

TEST(FlagGate, CheckeredFinishesTheLapThenStopsForGood) {
  FlagGate g({}, kStopBrake);
  g.flags(flags(0, TrackFlag::green, VehicleFlag::none, 0, 3));
  at(g, 0);
  g.flags(flags(1, TrackFlag::green, VehicleFlag::checkered, 0, 3));
  FlagTransition tr = at(g, 1);
  EXPECT_EQ(tr.to, RaceState::finishing);
  EXPECT_EQ(tr.reason, "CHECKERED at lap count 3: finishing the lap");
  EXPECT_EQ(g.apply(kRace, 1).throttle, kRace.throttle);  // racing to the line
  // A yellow on the way caps it; the lap still counts.
  g.flags(flags(2, TrackFlag::yellow, VehicleFlag::checkered, 20, 3));
  EXPECT_FALSE(at(g, 2).happened);
  EXPECT_TRUE(g.capped());
  g.flags(flags(40, TrackFlag::green, VehicleFlag::checkered, 0, 4));  // race control counted the lap
  tr = at(g, 40);
  EXPECT_EQ(tr.to, RaceState::finished);
  EXPECT_EQ(tr.reason, "the CHECKERED flag's lap finished (lap count 4): a controlled stop");
  EXPECT_DOUBLE_EQ(g.apply(kRace, 40).brake, kStopBrake);
  // Latched: the race is over whatever comes next.
  g.flags(flags(50, TrackFlag::green, VehicleFlag::none, 0, 4));
  EXPECT_FALSE(at(g, 50).happened);
  EXPECT_EQ(g.state(), RaceState::finished);
}

TEST(FlagGate, ACheckeredFlagBehindARedKeepsItsLap) {
  FlagGate g({}, kStopBrake);
  g.flags(flags(0, TrackFlag::green, VehicleFlag::checkered, 0, 7));
  EXPECT_EQ(at(g, 0).to, RaceState::finishing);
  g.flags(flags(1, TrackFlag::red, VehicleFlag::checkered, 0, 7));
  EXPECT_EQ(at(g, 1).to, RaceState::stopping);
  g.flags(flags(2, TrackFlag::green, VehicleFlag::checkered, 0, 7));
  EXPECT_EQ(at(g, 2).to, RaceState::finishing);
  g.flags(flags(3, TrackFlag::green, VehicleFlag::checkered, 0, 8));
  EXPECT_EQ(at(g, 3).to, RaceState::finished);
}

TEST(FlagGate, RaceControlLostStopsTheCarAndHeardAgainRaces) {
  FlagGate g({}, kStopBrake);
  g.flags(flags(0, TrackFlag::green));
  at(g, 0);
  // The interface says the heartbeat stopped.
  g.flags(flags(1, TrackFlag::green, VehicleFlag::none, 0, 0, false));
  FlagTransition tr = at(g, 1);
  EXPECT_EQ(tr.to, RaceState::stopping);
  EXPECT_EQ(tr.reason, "race control lost (its heartbeat stopped): a controlled stop at 6 m/s^2");
  g.flags(flags(2, TrackFlag::green));
  EXPECT_EQ(at(g, 2).to, RaceState::racing);
  // No message for more than timeout_s (0.5 s): the interface itself is silent.
  EXPECT_FALSE(at(g, 2.5).happened);
  tr = at(g, 2.51);
  EXPECT_EQ(tr.to, RaceState::stopping);
  EXPECT_EQ(tr.reason, "race control lost (no RaceControl message): a controlled stop at 6 m/s^2");
}

// A car that drives and brakes as the AV-21's file says (its drive and brake force linear in the
// pedals, no drag: the bound's worst case), the gate at 100 Hz: a yellow from 60 m/s brings it to
// 60 mph (within 0.5 m/s: the cap's brake eases off over the last 0.49 m/s) within
// (v0^2 - vt^2) / (2 x 6 m/s^2), and holds it there (never over, at most 0.5 m/s under); a red
// stops it within v0^2 / (2 x 6 m/s^2).
TEST(FlagGate, AYellowAndARedOnACarBrakeWithinTheirDistances) {
  const auto car = av21_vehicle();
  const double stop_brake = 6.0 * car.mass / car.max_brake_force;
  for (TrackFlag flag : {TrackFlag::yellow, TrackFlag::red}) {
    FlagGate g({}, stop_brake);
    const double v0 = 60, target = 60 * 0.44704;
    double v = v0, x = 0, reached_at = -1, lowest_after = 1e9, highest_after = 0;
    for (double t = 0; t < 30; t += 0.01) {
      g.flags(flags(t, flag, VehicleFlag::none, target));  // the interface publishes at 50 Hz or more
      g.speed(t, v);
      g.update(t);
      const Command c = g.apply({0, 1.0, 0, 90}, t);  // a tracker that wants more
      v = std::max(0.0, v + (c.throttle * car.max_drive_force - c.brake * car.max_brake_force) / car.mass * 0.01);
      x += v * 0.01;
      const double goal = flag == TrackFlag::yellow ? target : 0.0;
      if (reached_at < 0 && v <= goal + (flag == TrackFlag::yellow ? 0.5 : 0.01)) reached_at = x;
      if (reached_at >= 0) lowest_after = std::min(lowest_after, v), highest_after = std::max(highest_after, v);
    }
    const double goal = flag == TrackFlag::yellow ? target : 0.0;
    ASSERT_GE(reached_at, 0) << track_flag_name(flag);
    EXPECT_LE(reached_at, (v0 * v0 - goal * goal) / 12 + v0 * 0.01) << track_flag_name(flag);  // one step's travel
    EXPECT_LE(highest_after, goal + (flag == TrackFlag::yellow ? 0.5 : 0.01));
    if (flag == TrackFlag::yellow) {
      EXPECT_GE(lowest_after, goal - 0.5);
    }
  }
}
