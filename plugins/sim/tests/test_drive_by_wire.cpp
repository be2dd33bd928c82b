// The simulated drive-by-wire against the car's side of the interface, frame for frame in memory
// (the plugins put UDP between them): the command the simulated car gets is the stack's within a
// raw step of each signal, the reports come back, counters in order; its own stop when commands,
// their counters or the heartbeat stop; a lossy bus counted on both sides.
#include "sim/common/drive_by_wire.hpp"
#include "sim/common/stop_meter.hpp"
#include "vehicle_interface/common/raptor_interface.hpp"

#include "av21.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace brickyard;
using namespace brickyard::vehicle_interface;
using brickyard::sim::SimCarReading;
using brickyard::sim::SimDbwParams;
using brickyard::sim::SimDriveByWire;
using brickyard::sim::StopMeter;

namespace {

VehicleCanMapping av21_mapping() {
  static const DbcReadResult read = load_dbc_file(std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicle_interface/CAN1-INDY-V14.dbc");
  std::string error;
  std::optional<RaptorDbc> dbc = RaptorDbc::make(*read.database, "CAN1-INDY-V14.dbc", error);
  std::optional<DbwMaps> maps = dbw_maps(av21_vehicle(), "av21.json", error);
  return VehicleCanMapping(std::move(*dbc), std::move(*maps));
}

constexpr int64_t kMs = 1'000'000;

// Both sides stepped every 2 ms; the reports every 10 ms. `stack(t)` gives the stack's command at
// t (nullopt: none this step); `deliver(t)` whether the interface's frames reach the bus at t.
struct Loop {
  RaptorInterface iface{av21_mapping(), {}};
  SimDriveByWire dbw;
  SimCarReading car;
  motion::Command applied;
  explicit Loop(SimDbwParams p = {}, uint64_t seed = 1) : dbw(av21_mapping(), p, seed) { car.speed = 30; }

  template <class Stack, class Deliver> void run(int64_t from, int64_t to, Stack stack, Deliver deliver) {
    for (int64_t t = from; t < to; t += 2 * kMs) {
      if (const std::optional<motion::Command> c = stack(t)) iface.command(*c);
      const InterfaceStep s = iface.step(t);
      if (deliver(t)) dbw.receive(s.frames, t);
      applied = dbw.command(t);
      car.steer = applied.steer;
      car.wheel_fl = car.wheel_fr = car.wheel_rl = car.wheel_rr = car.speed;
      if (t % (10 * kMs) == 0) iface.receive(dbw.reports(car), t);
    }
  }
};

std::optional<motion::Command> every_10ms(int64_t t, motion::Command c) {
  return t % (10 * kMs) == 0 ? std::optional<motion::Command>(c) : std::nullopt;
}

}  // namespace

TEST(SimDriveByWire, DrivesTheCarWithTheStacksCommandWithinARawStep) {
  Loop loop;
  const motion::Command c{-0.123, 0.456, 0.0789, 30};
  loop.run(0, 2000 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return true; });
  EXPECT_NEAR(loop.applied.steer, c.steer, 0.25 / 15 * std::numbers::pi / 180);  // half of 0.5 motor deg
  EXPECT_NEAR(loop.applied.throttle, c.throttle, 0.00005);
  EXPECT_NEAR(loop.applied.brake, c.brake, 0.5 / 6000);
  EXPECT_FALSE(loop.dbw.stopping());
  EXPECT_EQ(loop.dbw.counts().timeouts, 0u);
  // Every command frame in order; the reports back, in order, none silent.
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(loop.dbw.counts().received[i], 200u) << i;
    EXPECT_EQ(loop.dbw.counts().skips[i] + loop.dbw.counts().repeats[i], 0u) << i;
  }
  EXPECT_EQ(loop.iface.monitor().total_skips(), 0u);
  EXPECT_EQ(loop.iface.monitor().total_silences(), 0u);
  EXPECT_NEAR(loop.iface.reports().wheel_rl, 30, 0.05 / 3.6);
  EXPECT_NEAR(loop.iface.reports().steer_motor_deg, c.steer * 180 / std::numbers::pi * 15, 0.5);
  EXPECT_EQ(loop.iface.reports().gear, loop.iface.setpoint().gear);  // the gearbox shifts at once
  EXPECT_EQ(loop.iface.reports().gear, 2);  // 30 m/s: 8356 rpm in first, 5372 in second
  EXPECT_NEAR(loop.iface.reports().brake_front_kpa, c.brake * 6000, 0.5);
}

// The interface's frames stop reaching the bus at 1 s (its process gone): 0.2 s later the
// simulated drive-by-wire stops the car itself, and says the heartbeat is lost.
TEST(SimDriveByWire, BrakesOnItsOwnWhenTheFramesStop) {
  Loop loop;
  const motion::Command c{0.01, 0.8, 0, 30};
  loop.run(0, 1000 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return true; });
  EXPECT_FALSE(loop.dbw.stopping());
  loop.run(1000 * kMs, 1190 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return false; });
  EXPECT_FALSE(loop.dbw.stopping());  // the last frames at 0.99 s: 0.198 s old
  loop.run(1190 * kMs, 1300 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return false; });
  EXPECT_TRUE(loop.dbw.stopping());
  EXPECT_TRUE(loop.dbw.heartbeat_lost());
  EXPECT_EQ(loop.applied.throttle, 0);
  EXPECT_EQ(loop.applied.brake, 0.6);
  EXPECT_NEAR(loop.applied.steer, 0.01, 0.001);  // held
  EXPECT_EQ(loop.iface.reports().diagnostic_bits, raptor_diagnostic_mask("adlink_hb_lost"));
  EXPECT_EQ(loop.dbw.counts().timeouts, 1u);
  // Back: it drives again.
  loop.run(1300 * kMs, 1400 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return true; });
  EXPECT_FALSE(loop.dbw.stopping());
  EXPECT_NEAR(loop.applied.throttle, 0.8, 0.0001);
}

// stop_steering centre: its own stop straightens the wheel; the commands back steer again.
TEST(SimDriveByWire, ItsOwnStopCanCentreTheWheel) {
  SimDbwParams p;
  p.centre_steering = true;
  Loop loop(p);
  const motion::Command c{0.01, 0.8, 0, 30};
  loop.run(0, 1000 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return true; });
  EXPECT_NEAR(loop.applied.steer, 0.01, 0.001);
  loop.run(1000 * kMs, 1300 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return false; });
  EXPECT_TRUE(loop.dbw.stopping());
  EXPECT_EQ(loop.applied.steer, 0);
  EXPECT_EQ(loop.applied.brake, 0.6);
  loop.run(1300 * kMs, 1400 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return true; });
  EXPECT_NEAR(loop.applied.steer, 0.01, 0.001);
}

// The stack stops commanding: the interface brakes the car to a stop and, standing, stops the
// heartbeat; the simulated drive-by-wire then holds the car with its own stop.
TEST(SimDriveByWire, TheInterfacesHandoverIsTheDriveByWiresStop) {
  Loop loop;
  const motion::Command c{0, 0.5, 0, 30};
  loop.run(0, 1000 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return true; });
  const auto none = [](int64_t) { return std::optional<motion::Command>(); };
  for (int64_t t = 1000 * kMs; t < 9000 * kMs && !loop.dbw.heartbeat_lost(); t += 10 * kMs) {
    loop.run(t, t + 10 * kMs, none, [](int64_t) { return true; });
    if (loop.applied.brake > 0) loop.car.speed = std::max(0.0, loop.car.speed - 6 * 0.01);  // the test's car: 6 m/s^2
  }
  EXPECT_EQ(loop.iface.watchdog().state(), DbwState::handed_over);
  EXPECT_TRUE(loop.dbw.heartbeat_lost());
  EXPECT_EQ(loop.car.speed, 0);
  EXPECT_NEAR(loop.iface.watchdog().stop_distance_m(), 30.0 * 30 / 12, 1.0);
  // Until the handover the drive-by-wire drove what the interface asked: the stop brake, no own stop.
  EXPECT_EQ(loop.dbw.counts().timeouts, 1u);
  EXPECT_EQ(loop.applied.brake, 0.6);
}

// Frames whose counters repeat are a sender that is stuck: they do not keep the car going.
TEST(SimDriveByWire, RepeatedCountersAreNoSignOfLife) {
  const VehicleCanMapping map = av21_mapping();
  SimDriveByWire dbw(map, {}, 1);
  DbwSetpoint s;
  s.actuation.accelerator_pct = 50;
  for (int64_t t = 0; t < 500 * kMs; t += 10 * kMs) {
    std::vector<CanFrame> frames;
    for (RaptorMessage m : kRaptorCommands) frames.push_back(map.command_frame(m, s, 7).frame);  // always 7
    dbw.receive(frames, t);
    dbw.command(t);
  }
  EXPECT_TRUE(dbw.stopping());
  EXPECT_EQ(dbw.counts().repeats[0], 49u);
  EXPECT_EQ(dbw.counts().received[0], 50u);
}

// 5 % of the frames lost each way, at random: both sides count the gaps, and the car never stops
// (0.2 s of commands would have to be lost in a row).
TEST(SimDriveByWire, ALossyBusIsCountedAndStillDrives) {
  SimDbwParams p;
  p.loss = 0.05;
  Loop loop(p, 7);
  const motion::Command c{0.02, 0.6, 0, 30};
  loop.run(0, 20000 * kMs, [&](int64_t t) { return every_10ms(t, c); }, [](int64_t) { return true; });
  const sim::SimDbwCounts& n = loop.dbw.counts();
  const double in = static_cast<double>(n.lost_in) / static_cast<double>(n.lost_in + n.frames_in);
  EXPECT_NEAR(in, 0.05, 0.01);  // of 10 000 frames
  EXPECT_GT(n.lost_out, 400u);  // of 12 000 reports
  EXPECT_LT(n.lost_out, 800u);
  EXPECT_GT(n.skips[2], 50u);  // steering_cmd's counter skipped where frames were lost
  EXPECT_EQ(n.timeouts, 0u);
  EXPECT_GT(loop.iface.monitor().counts(RaptorMessage::steering_report).skips, 50u);
  EXPECT_EQ(loop.iface.monitor().total_silences(), 0u);
  EXPECT_NEAR(loop.applied.throttle, 0.6, 0.0001);
}

// A stop from 40 m/s at a steady 8 m/s^2, sampled at 500 Hz: v0^2 / (2 a) = 100 m.
TEST(StopMeter, MeasuresTheDistanceToStandstill) {
  StopMeter m;
  m.begin(10.0, 40.0);
  for (int k = 1; k <= 3000; ++k) m.sample(10.0 + k * 0.002, std::max(0.0, 40.0 - 8.0 * k * 0.002));
  EXPECT_TRUE(m.stood());
  EXPECT_FALSE(m.measuring());
  EXPECT_DOUBLE_EQ(m.from_speed_mps(), 40.0);
  EXPECT_NEAR(m.distance_m(), 100.0, 0.01);
}

TEST(StopMeter, AStopCalledOffMeasuresNothing) {
  StopMeter m;
  m.begin(0.0, 30.0);
  m.sample(0.5, 28.0);
  m.abandon();
  m.sample(1.0, 0.0);
  EXPECT_FALSE(m.stood());
  EXPECT_NEAR(m.distance_m(), 14.5, 1e-9);  // what it ran before the stop was called off
}
