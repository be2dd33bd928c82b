// The simulator's algorithms, called directly (no framework): track files, banking, the vehicle
// model against the analytical bicycle model, LiDAR ray casting, fault windows, the referee.
#include "sim/common/car_contacts.hpp"
#include "sim/common/car_on_track.hpp"
#include "sim/common/command_watchdog.hpp"
#include "sim/common/step_span.hpp"
#include "sim/common/driver_line.hpp"
#include "sim/common/faults.hpp"
#include "sim/common/gnss_receiver.hpp"
#include "sim/common/lidar.hpp"
#include "sim/common/localization_samples.hpp"
#include "sim/common/localization_score.hpp"
#include "sim/common/perception_score.hpp"
#include "sim/common/race_judge.hpp"
#include "sim/common/referee.hpp"
#include "sim/common/scanner.hpp"
#include "sim/common/track.hpp"
#include "sim/common/vehicle_model.hpp"
#include "sim/common/world_builder.hpp"

#include "av21.hpp"
#include "motion/vehicle_limits.hpp"
#include "track/band_overlap.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <unistd.h>

using namespace brickyard::sim;

namespace {

// A stadium oval, counter-clockwise: straights of `straight` m along x, half circles of radius r.
CenterLine oval(double straight = 1000, double r = 200, double half_width = 7.5) {
  CenterLine c;
  auto add = [&](double x, double y) {
    c.x.push_back(x); c.y.push_back(y); c.width_left.push_back(half_width); c.width_right.push_back(half_width);
  };
  const double step = 5;
  for (double s = 0; s < straight; s += step) add(s, 0);
  int n = static_cast<int>(std::round(M_PI * r / step));
  for (int i = 0; i < n; ++i) {
    double a = -M_PI / 2 + M_PI * i / n;
    add(straight + r * std::cos(a), r + r * std::sin(a));
  }
  for (double s = 0; s < straight; s += step) add(straight - s, 2 * r);
  for (int i = 0; i < n; ++i) {
    double a = M_PI / 2 + M_PI * i / n;
    add(r * std::cos(a), r + r * std::sin(a));
  }
  return c;
}

Eigen::Isometry3d pose_on(const Track& t, double s, double d, double yaw_offset = 0) {
  Frenet f = t.at(s, d);
  Eigen::Vector2d p = t.position(f), g = t.road_gradient(f);
  double yaw = t.heading(f) + yaw_offset, c = std::cos(yaw), sn = std::sin(yaw);
  double pitch = -std::atan(g.x() * c + g.y() * sn), roll = std::atan(-g.x() * sn + g.y() * c);
  return Eigen::Translation3d(p.x(), p.y(), t.road_z(f)) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
}

std::string ims_path() { return std::string(BRICKYARD_SOURCE_DIR) + "/data/tracks/IMS.csv"; }

// IMS banked by curvature, the outer wall on, two pylons: the world of the caster comparisons.
WorldSpec ims_banked_with_pylons() {
  WorldSpec w;
  w.line = load_centerline_csv(ims_path());
  BankSpec b;
  b.mode = "curvature";
  b.degrees = 9.2;
  b.curvature_threshold = 0.002;
  w.bank = bank_profile(w.line, b);
  w.walls.right = true;
  w.pylons = {Pylon{300, 2, 0.2, 0.7}, Pylon{1200, -1, 0.3, 1.0}};
  return w;
}

}  // namespace

TEST(TrackFile, BadRowNamesFileAndLine) {
  std::istringstream in("# x_m,y_m,w_tr_right_m,w_tr_left_m\n0,0,7,7\n0,-5,7,7\n\n0,-10,7\n0,-15,7,7\n");
  try {
    parse_centerline_csv(in, "t.csv");
    FAIL() << "no error";
  } catch (const TrackFileError& e) {
    EXPECT_STREQ(e.what(), "t.csv:5: 3 fields, expected 4");
  }
  std::istringstream neg("0,0,7,7\n0,-5,-1,7\n");
  EXPECT_THROW(parse_centerline_csv(neg, "n.csv"), TrackFileError);
}

// Values no circuit has are refused naming the line (x = 1e308 made a track "of length inf").
TEST(TrackFile, ValuesNoCircuitHasAreRefused) {
  auto error = [](const std::string& text) {
    std::istringstream in(text);
    try {
      parse_centerline_csv(in, "t.csv");
    } catch (const TrackFileError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string square = "0,0,7,7\n50,0,7,7\n50,50,7,7\n0,50,7,7\n";
  EXPECT_EQ(error(square), "");
  EXPECT_EQ(error("0,0,7,7\n1e308,0,7,7\n50,50,7,7\n0,50,7,7\n"), "t.csv:2: a point more than 1000 km from the origin");
  EXPECT_EQ(error("0,0,7,7\n50,0,700,7\n50,50,7,7\n0,50,7,7\n"), "t.csv:2: a track width over 100 m");
  // Decimal numbers only: a hexadecimal float (strtod's) is not a track's.
  EXPECT_EQ(error("0,0,7,7\n0x1.9p5,0,7,7\n50,50,7,7\n0,50,7,7\n"), "t.csv:2: field 1 is not a number: '0x1.9p5'");
  EXPECT_EQ(error("0,0,7,7\n50.0,-0.0,7e0,7.\n50,50,7,7\n0,50,7,7\n"), "");
  EXPECT_EQ(error("0,0,7,7\n500,0,7,7\n50,50,7,7\n0,50,7,7\n"), "t.csv:2: 500 m from the point of line 1 (points at most 200 m apart)");
  EXPECT_EQ(error("0,0,7,7\n150,0,7,7\n300,0,7,7\n450,0,7,7\n"),
            "t.csv: not a closed loop: its last point (line 4) is 450 m from its first (at most 200 m)");
  // A C: 5 m apart, and its ends 60 m apart.
  std::string c_shape;
  for (int i = 0; i <= 60; ++i) {
    const double a = M_PI / 2 + 1.6 * M_PI * i / 60;
    c_shape += std::to_string(100 * std::cos(a)) + "," + std::to_string(100 * std::sin(a)) + ",6,6\n";
  }
  EXPECT_NE(error(c_shape).find("t.csv: not a closed loop: its last point (line 61) is "), std::string::npos) << error(c_shape);
  EXPECT_NE(error(c_shape).find("more than 4 times its points' usual spacing (8.4 m)"), std::string::npos) << error(c_shape);
}

// A track whose band runs over itself is refused naming two lines where it does (figure
// 8s and self-overlapping tracks were read, and every lateral coordinate was ambiguous there); a
// steep crossing is a bridge, read and said (Suzuka's, at 60 degrees, races: docs/security.md).
TEST(TrackFile, ABandOverItselfIsRefused) {
  auto error = [](const std::vector<std::array<double, 4>>& pts) {
    std::ostringstream f;
    for (const auto& p : pts) f << p[0] << "," << p[1] << "," << p[2] << "," << p[3] << "\n";
    std::istringstream in(f.str());
    try {
      parse_centerline_csv(in, "t.csv");
    } catch (const TrackFileError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // A stadium: two 500 m straights joined by half circles of radius r, track 2w wide.
  auto stadium = [](double r, double w) {
    std::vector<std::array<double, 4>> p;
    for (int i = 0; i < 100; ++i) p.push_back({i * 5.0, 0, w, w});
    for (int i = 0; i < 40; ++i) {
      const double t = -M_PI / 2 + M_PI * i / 40;
      p.push_back({500 + r * std::cos(t), r + r * std::sin(t), w, w});
    }
    for (int i = 0; i < 100; ++i) p.push_back({500 - i * 5.0, 2 * r, w, w});
    for (int i = 0; i < 40; ++i) {
      const double t = M_PI / 2 + M_PI * i / 40;
      p.push_back({r * std::cos(t), r + r * std::sin(t), w, w});
    }
    return p;
  };
  EXPECT_EQ(error(stadium(30, 7)), "");  // straights 60 m apart, 14 m of track facing: a circuit
  EXPECT_EQ(error(stadium(5, 7)),
            "t.csv: the track runs over itself: near lines 4 and 238 two stretches are 10.00 m apart centre to "
            "centre, less than their facing widths together (14.00 m)");
  // The widths that face each other count, not the far sides'.
  auto lopsided = stadium(5, 7);
  for (auto& q : lopsided) q[3] = 1, q[2] = 20;  // 1 m on the left (inside), 20 m on the right (outside)
  EXPECT_EQ(error(lopsided), "");
  // A figure 8 whose two stretches cross at a shallow angle lies one over the other: refused.
  auto eight = [](double height) {
    std::vector<std::array<double, 4>> p;
    for (int i = 0; i < 201; ++i) p.push_back({400 * std::sin(2 * M_PI * i / 201), height * std::sin(4 * M_PI * i / 201), 6, 6});
    return p;
  };
  EXPECT_EQ(error(eight(40)),
            "t.csv: its centre line crosses itself between lines 1 and 102 at 23 degrees: two stretches over each other, "
            "not a bridge (one of at least 30 degrees)");
  // At a steep angle it is a bridge, as at Suzuka: read, and said once.
  EXPECT_EQ(error(eight(300)), "");
  std::ostringstream f;
  for (const auto& p : eight(300)) f << p[0] << "," << p[1] << "," << p[2] << "," << p[3] << "\n";
  std::istringstream in(f.str());
  const CenterLine c = parse_centerline_csv(in, "t.csv");
  EXPECT_EQ(c.notes, std::vector<std::string>{"t.csv: the track crosses itself between lines 1 and 102 at 67 degrees: a bridge"});
}

// The real tracks pass with room to spare: still read with every width doubled.
TEST(TrackFile, RealTracksAreFarFromOverlapping) {
  for (const char* name : {"IMS", "Monza", "Spielberg", "Hockenheim"}) {
    CenterLine c = load_centerline_csv(std::string(BRICKYARD_SOURCE_DIR) + "/data/tracks/" + name + ".csv");
    for (auto& w : c.width_left) w *= 2;
    for (auto& w : c.width_right) w *= 2;
    const brickyard::track::BandCheck band = brickyard::track::check_band(c);
    EXPECT_FALSE(band.overlap.has_value()) << name;
    EXPECT_TRUE(band.bridges.empty()) << name;
  }
}

TEST(TrackFile, ImsLoadsClosedCounterClockwise) {
  WorldSpec w;
  w.line = load_centerline_csv(ims_path());
  Track t(w);
  EXPECT_NEAR(t.length(), 4022, 5);
  EXPECT_TRUE(t.counter_clockwise());
}

TEST(Banking, CurvatureModeRaisesTheOutsideOfImsTurns) {
  CenterLine c = load_centerline_csv(ims_path());
  BankSpec b;
  b.mode = "curvature";
  b.degrees = 9.2;
  b.curvature_threshold = 0.002;
  auto bank = bank_profile(c, b);
  auto k = signed_curvature(c, 50);
  int turn = 0, straight = 0;
  for (std::size_t i = 0; i < bank.size(); ++i) {
    if (k[i] > 0.003) {  // inside a left turn: the right (outside) edge is raised, fully past the ramps
      EXPECT_LT(bank[i], 0) << i;
      turn += std::abs(bank[i] + 9.2 * M_PI / 180) < 1e-9;
    }
    if (std::abs(k[i]) < 1e-4 && bank[i] == 0) ++straight;
  }
  EXPECT_GT(turn, 100);
  EXPECT_GT(straight, 100);
}

TEST(Track, ProjectionRoundTrip) {
  WorldSpec w;
  w.line = oval();
  Track t(w);
  for (double s : {3.0, 500.0, 1100.0, 1700.0, 2500.0})
    for (double d : {-5.0, 0.0, 6.0}) {
      Frenet f = t.at(s, d);
      Eigen::Vector2d p = t.position(f);
      Frenet g = t.project(p.x(), p.y());
      EXPECT_NEAR(g.s, s, 1e-6);
      EXPECT_NEAR(g.d, d, 1e-6);
    }
}

// Steady-state cornering of the linear single-track model: yaw rate r = v delta / (L + K v^2)
// with the understeer gradient K = m (lr / Cf - lf / Cr) / L.
TEST(Vehicle, SteadyStateCorneringMatchesTheBicycleModel) {
  VehicleParams p = av21_vehicle();
  p.tyre = "linear";
  p.mu = 100;  // no saturation
  p.drag_area = p.lift_area = p.rolling_resistance = 0;
  p.steer_delay = 0;
  p.max_steer_rate = 10;
  const double L = p.lf + p.lr;
  const double K = p.mass * (p.lr / p.cornering_front - p.lf / p.cornering_rear) / L;
  for (double v : {15.0, 30.0, 50.0}) {
    VehicleModel m(p);
    m.state().vx = v;
    const double delta = 0.02;
    for (int i = 0; i < 500 * 20; ++i) {
      Command c;
      c.steer = delta;
      double e = v - m.state().vx;  // hold the speed
      c.throttle = std::clamp(0.5 * e, 0.0, 1.0);
      c.brake = std::clamp(-0.5 * e, 0.0, 1.0);
      m.step(0.002, c, Eigen::Vector2d::Zero());
    }
    const double r_expected = v * delta / (L + K * v * v);
    EXPECT_NEAR(m.state().vx, v, 0.05 * v);
    EXPECT_NEAR(m.state().r, m.state().vx * delta / (L + K * m.state().vx * m.state().vx), 0.02 * r_expected) << v;
  }
}

TEST(Vehicle, SlopedRoadPullsTheCarDownhill) {
  VehicleModel m(av21_vehicle());
  // Rolling slowly (kinematic regime) with the nose up a 10 % slope and no drive: gravity along
  // the road, g * 0.1, plus rolling resistance and drag slows the car.
  const VehicleParams p = av21_vehicle();
  m.state().vx = 2.0;
  m.step(0.002, Command{}, Eigen::Vector2d(0.1, 0));
  const double drag = 0.5 * p.air_density * 4.0 * p.drag_area / p.mass;
  EXPECT_NEAR(m.state().ax, -brickyard::vehicle::gravity * 0.1 - p.rolling_resistance * brickyard::vehicle::gravity - drag, 1e-9);
}

TEST(Lidar, RayToAWallAtAKnownDistance) {
  WorldSpec w;
  w.line = oval();
  w.walls.left = w.walls.right = true;
  w.walls.left_offset = 0.5;
  w.walls.right_offset = 1.0;
  Track t(w);
  LidarSpec s;
  s.mount = {0, 0, 0.5};
  s.elevations = {0.0};
  s.columns = 1;
  s.range_noise = 0.02;
  LidarCaster c(t, s);
  // Car on the straight at s = 400, d = 1, level road: left wall at d = 8, right wall at d = -8.5.
  Frenet f = t.at(400, 1.0);
  Eigen::Vector3d o(t.position(f).x(), t.position(f).y(), 0.5);
  RayHit left = c.cast(o, Eigen::Vector3d(0, 1, 0), f.seg);
  EXPECT_EQ(left.surface, Surface::wall);
  EXPECT_NEAR(left.range, 7.0, 1e-9);
  RayHit right = c.cast(o, Eigen::Vector3d(0, -1, 0), f.seg);
  EXPECT_NEAR(right.range, 9.5, 1e-9);
  // A slanted ray: 45 deg to the left and forward crosses 7 m of lateral distance in 7 sqrt(2).
  RayHit slant = c.cast(o, Eigen::Vector3d(1, 1, 0).normalized(), f.seg);
  EXPECT_NEAR(slant.range, 7 * std::sqrt(2.0), 1e-9);
  // Through scan(): the sensor looking left (yaw 90 deg) with noise: within 4 sigma.
  Rng rng(3);
  PointBuffers out;
  int within = 0;
  for (int i = 0; i < 200; ++i) {
    out.clear();
    c.scan(Eigen::Translation3d(o.x(), o.y(), 0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()), f.seg, rng, 1.0, out);
    ASSERT_EQ(out.x.size(), 1u);
    within += std::abs(out.x[0] - 7.0) < 4 * 0.02;
  }
  EXPECT_EQ(within, 200);
  // A ray above the wall (1.2 m high) meets nothing; one aimed at the road ahead hits it.
  EXPECT_EQ(c.cast(o, Eigen::Vector3d(0, 1, 0.3).normalized(), f.seg).surface, Surface::none);
  RayHit road = c.cast(o, Eigen::Vector3d(1, 0, -0.05).normalized(), f.seg);
  EXPECT_EQ(road.surface, Surface::road);
  EXPECT_NEAR(road.range, 0.5 / std::sin(std::atan(0.05)), 1e-4);
}

// Beyond the road's edge, short of the wall, the ground is grass: a mapping drive sees the edge
// by the grass's brighter returns (docs/mapping.md).
TEST(Lidar, TheGroundBeyondTheEdgeIsGrassAndReturnsMoreLight) {
  WorldSpec w;
  w.line = oval();
  w.walls.left = true;
  w.walls.left_offset = 1.0;  // the left edge at d = 7.5, its wall at 8.5
  Track t(w);
  const Frenet f = t.at(400, 1.0);
  const Eigen::Vector3d o(t.position(f).x(), t.position(f).y(), 0.5);
  LidarSpec s;
  s.mount = {0, 0, 0.5};
  s.columns = 1;
  s.range_noise = 0;
  auto hit = [&](double lateral) {  // the ray down to the ground `lateral` metres to the left
    s.elevations = {-std::atan(0.5 / lateral)};
    LidarCaster c(t, s);
    const RayHit h = c.cast(o, Eigen::Vector3d(0, lateral, -0.5).normalized(), f.seg);
    Rng rng(1);
    PointBuffers out;
    c.scan(Eigen::Translation3d(o.x(), o.y(), 0) * Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()), f.seg, rng, 0.0, out);
    EXPECT_EQ(out.intensity.size(), 1u);
    return std::make_pair(h.surface, out.intensity.empty() ? -1.0 : out.intensity[0] / h.cos_incidence);
  };
  const auto road = hit(6.0), grass = hit(7.0);  // d = 7 on the road, d = 8 beyond its edge
  EXPECT_EQ(road.first, Surface::road);
  EXPECT_EQ(grass.first, Surface::grass);
  EXPECT_NEAR(road.second, LidarSpec{}.reflectivity_road, 1e-5);
  EXPECT_NEAR(grass.second, LidarSpec{}.reflectivity_grass, 1e-5);
}

TEST(Lidar, PointsOnTheBankedTurnLieOnTheBankedSurface) {
  WorldSpec w;
  w.line = load_centerline_csv(ims_path());
  BankSpec b;
  b.mode = "constant";
  b.degrees = 9.2;
  w.bank = bank_profile(w.line, b);
  w.walls.right = true;
  Track t(w);
  LidarSpec s;
  s.mount = {2.342, 0, 0.448};
  s.elevations = row_elevations(32, -15, 15, "horizon", 2);
  s.range_noise = 0;
  LidarCaster c(t, s);
  // In turn 1 of IMS (about 1/4 of the way round), on the low side of the track.
  Eigen::Isometry3d body = pose_on(t, 700, 3.0);
  Eigen::Isometry3d sensor = body * Eigen::Translation3d(s.mount);
  Rng rng(1);
  PointBuffers out;
  c.scan(body, t.project(body.translation().x(), body.translation().y()).seg, rng, 1.0, out);
  int road = 0;
  double worst = 0;
  for (std::size_t i = 0; i < out.x.size(); ++i) {
    Eigen::Vector3d p = sensor * Eigen::Vector3d(out.x[i], out.y[i], out.z[i]);
    Frenet f = t.project(p.x(), p.y());
    if (f.d < -t.width_right(f.seg, f.u) + 0.05 || f.d > t.width_left(f.seg, f.u) - 0.05) continue;  // walls
    if (std::abs(p.z() - t.road_z(f)) > 0.3) continue;                                               // walls
    worst = std::max(worst, std::abs(p.z() - t.road_z(f)));
    ++road;
  }
  EXPECT_GT(road, 5000);
  // The caster's surface is defined slab by slab (d across the slab's segment); the projection
  // here takes the nearest segment. On the turn's outside the two differ by up to ~2 cm.
  EXPECT_LT(worst, 0.03);
  // The banked surface is not level: points well across the track differ in height by metres.
  double zmin = 1e9, zmax = -1e9;
  for (std::size_t i = 0; i < out.x.size(); ++i) {
    Eigen::Vector3d p = sensor * Eigen::Vector3d(out.x[i], out.y[i], out.z[i]);
    zmin = std::min(zmin, p.z());
    zmax = std::max(zmax, p.z());
  }
  EXPECT_GT(zmax - zmin, 2.0);
}

TEST(Lidar, BlockSkippingReturnsWhatTheSlabMarchReturns) {
  Track t(ims_banked_with_pylons());
  LidarSpec s;
  s.elevations = row_elevations(32, -15, 15, "horizon", 2);
  s.columns = 200;
  s.range_noise = 0;
  s.coherent_columns = false;
  LidarSpec plain = s;
  plain.use_blocks = false;
  LidarCaster fast(t, s), slow(t, plain);
  std::size_t n = 0, differ = 0;
  for (double at = 0; at < t.length(); at += 97) {
    Eigen::Isometry3d body = pose_on(t, at, -2.0);
    int seg = t.project(body.translation().x(), body.translation().y()).seg;
    Rng r1(1), r2(1);
    PointBuffers a, c;
    fast.scan(body, seg, r1, 1.0, a);
    slow.scan(body, seg, r2, 1.0, c);
    n += c.x.size();
    if (a.x.size() != c.x.size()) { differ += 1000; continue; }
    for (std::size_t i = 0; i < a.x.size(); ++i)
      differ += std::abs(a.x[i] - c.x[i]) + std::abs(a.y[i] - c.y[i]) + std::abs(a.z[i] - c.z[i]) > 1e-3;
  }
  EXPECT_GT(n, 40000u);
  EXPECT_EQ(differ, 0u);
}

// A column's rows resume where the row below left off, and stop once one escapes; every ray
// cast alone from the sensor must return the same (to a millimetre: the root is found from
// another start). Poses on the banking (tilted columns), all three mounts, pylons in view.
TEST(Lidar, CoherentColumnsReturnWhatEveryRayAloneReturns) {
  Track t(ims_banked_with_pylons());
  std::size_t n = 0, differ = 0, pylon_points = 0;
  double worst = 0;
  for (double yaw : {0.0, 120.0, -120.0}) {
    LidarSpec s;
    s.mount = {1.5, 0, 0.5};
    s.yaw = yaw * M_PI / 180;
    s.elevations = row_elevations(32, -15, 15, "horizon", 2);
    s.columns = 300;
    s.range_noise = 0;
    LidarSpec alone = s;
    alone.coherent_columns = false;
    LidarCaster coherent(t, s), single(t, alone);
    for (double at = 0; at < t.length(); at += 97) {
      Eigen::Isometry3d body = pose_on(t, at, -2.0);
      int seg = t.project(body.translation().x(), body.translation().y()).seg;
      Rng r1(1), r2(1);
      PointBuffers a, c;
      coherent.scan(body, seg, r1, 1.0, a);
      single.scan(body, seg, r2, 1.0, c);
      n += c.x.size();
      ASSERT_EQ(a.x.size(), c.x.size()) << "at s = " << at << ", yaw " << yaw;
      for (std::size_t i = 0; i < a.x.size(); ++i) {
        const double e = std::abs(a.x[i] - c.x[i]) + std::abs(a.y[i] - c.y[i]) + std::abs(a.z[i] - c.z[i]);
        worst = std::max(worst, e);
        differ += e > 1e-3;
        pylon_points += c.intensity[i] > 0.5f * s.reflectivity_pylon;
      }
    }
  }
  EXPECT_GT(n, 100000u);
  EXPECT_GT(pylon_points, 10u);
  EXPECT_LT(worst, 0.005);
  EXPECT_LT(differ, n / 10000);
}

namespace {

// IMS with walls on both sides and pylons beside the line: where the lanes part ways most and the
// escape argument is weakest.
WorldSpec walled_with_pylons() {
  WorldSpec w = ims_banked_with_pylons();
  w.walls.left = true;
  w.walls.left_offset = 0.5;
  for (double s = 100; s < 3900; s += 450) w.pylons.push_back(Pylon{s, 3.5, 0.25, 1.0});
  return w;
}

// Frames cast by two casters from the same poses (every `step` m from `first`, at each offset in
// `ds`, turned a little towards the nearer wall) with the same seed must be the same, bit for bit,
// surfaces included. Returns the points compared.
std::size_t same_frames(const Track& t, const LidarSpec& sa, const LidarSpec& sb, double first, double step,
                        std::initializer_list<double> ds, std::uint64_t seed) {
  LidarCaster ca(t, sa), cb(t, sb);
  std::size_t n = 0;
  for (double at = first; at < t.length(); at += step)
    for (double d : ds) {
      Eigen::Isometry3d body = pose_on(t, at, d, (d > 0 ? -1 : 1) * 0.03);
      int seg = t.project(body.translation().x(), body.translation().y()).seg;
      Rng r1(seed), r2(seed);
      PointBuffers a, b;
      a.record_surface = b.record_surface = true;
      ca.scan(body, seg, r1, 1.0, a);
      cb.scan(body, seg, r2, 1.0, b);
      n += b.x.size();
      EXPECT_TRUE(a.x == b.x && a.y == b.y && a.z == b.z && a.intensity == b.intensity && a.surface == b.surface)
          << "at s = " << at << ", d " << d << ", roll " << sa.roll << ", yaw " << sa.yaw;
      if (::testing::Test::HasFailure()) return n;
    }
  return n;
}

LidarSpec rolled_hydra(double roll_deg, double yaw_deg, int columns) {
  LidarSpec s;
  s.mount = {1.5, 0, 0.5};
  s.roll = roll_deg * M_PI / 180;
  s.yaw = yaw_deg * M_PI / 180;
  s.elevations = row_elevations(32, -15, 15, "horizon", 2);
  s.columns = columns;
  return s;
}

}  // namespace

// Once a row escapes, the rows above it are not cast when an argument says they meet nothing
// (LidarCaster::rows_above_escape). Stress it where it is weakest: the sensor rolled hard (the rows
// above drift sideways), close to walls on both sides, looking along them, pylons beside the line.
// Casting those rows anyway must give the very same frame, bit for bit, in the lanes and ray by ray.
TEST(Lidar, SkippedRowsAboveAnEscapeReturnNothing) {
  Track t(walled_with_pylons());
  for (bool simd : {true, false}) {
    std::size_t n = 0;
    for (double roll : {-40.0, -20.0, 0.0, 25.0, 45.0})
      for (double yaw : {0.0, 60.0, -60.0}) {
        LidarSpec s = rolled_hydra(roll, yaw, 240);
        s.simd = simd;
        LidarSpec all = s;
        all.skip_escaped_rows = false;
        n += same_frames(t, s, all, 40, 233, {-9.0, 0.0, 9.0}, 1);
        if (HasFailure()) return;
      }
    EXPECT_GT(n, 200000u) << "simd " << simd;
  }
}

// The rays of four columns marched together in AVX2 lanes must give the very frame the rays
// cast one by one give, bit for bit (noise, surfaces and all), where the lanes part ways most.
// (Without AVX2 both are the one-by-one scan.)
TEST(Lidar, LanesReturnWhatRaysOneByOneReturn) {
  Track t(walled_with_pylons());
  std::size_t n = 0;
  for (double roll : {-30.0, 0.0, 20.0})
    for (double yaw : {0.0, 120.0, -120.0}) {
      LidarSpec s = rolled_hydra(roll, yaw, 243);  // not a multiple of 4: a last group of 3
      LidarSpec one = s;
      one.simd = false;
      n += same_frames(t, s, one, 20, 311, {-6.0, 0.0, 6.0}, 3);
      if (HasFailure()) return;
    }
  EXPECT_GT(n, 100000u);
}

// The columns marched on two threads (the noise drawn afterwards in one order): the same frames,
// bit for bit, as on one.
TEST(Lidar, TwoThreadsReturnWhatOneReturns) {
  Track t(walled_with_pylons());
  std::size_t n = 0;
  for (double roll : {-30.0, 20.0}) {
    LidarSpec two = rolled_hydra(roll, 0.0, 243);
    LidarSpec one = two;
    one.threads = 1;
    n += same_frames(t, two, one, 20, 311, {-6.0, 0.0, 6.0}, 3);
    if (HasFailure()) return;
  }
  EXPECT_GT(n, 10000u);
}

// The Ziggurat normal generator: moments, the tails (beyond R = 3.44 it samples the tail
// separately), a binned chi-square against the normal CDF, and the same numbers for the same seed.
TEST(Rng, ZigguratNormalsAreStandardNormal) {  // normal_fast, the LiDAR range noise
  Rng rng(7);
  const int n = 2000000;
  double s1 = 0, s2 = 0;
  int over2 = 0, over3 = 0, over4 = 0;
  std::vector<int> bins(80, 0);  // [-4, 4) in steps of 0.1
  for (int i = 0; i < n; ++i) {
    const double x = rng.normal_fast();
    s1 += x;
    s2 += x * x;
    over2 += std::abs(x) > 2;
    over3 += std::abs(x) > 3;
    over4 += std::abs(x) > 4;
    const int b = static_cast<int>(std::floor((x + 4) * 10));
    if (b >= 0 && b < 80) ++bins[b];
  }
  // Bounds at about 5 standard errors of each estimate.
  EXPECT_NEAR(s1 / n, 0.0, 0.0035);
  EXPECT_NEAR(s2 / n, 1.0, 0.005);
  EXPECT_NEAR(static_cast<double>(over2) / n, 0.0455003, 5 * 1.5e-4);
  EXPECT_NEAR(static_cast<double>(over3) / n, 0.0026998, 5 * 3.7e-5);
  EXPECT_NEAR(static_cast<double>(over4) / n, 6.334e-5, 5 * 5.6e-6);
  double chi2 = 0;
  for (int b = 0; b < 80; ++b) {
    const double lo = b / 10.0 - 4, hi = lo + 0.1;
    const double e = n * 0.5 * (std::erf(hi / std::sqrt(2.0)) - std::erf(lo / std::sqrt(2.0)));
    chi2 += (bins[b] - e) * (bins[b] - e) / e;
  }
  EXPECT_LT(chi2, 130);  // 79 degrees of freedom: P(chi2 > 130) < 1e-3
  Rng a(11), b(11);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.normal_fast(), b.normal_fast());
}

TEST(Faults, WindowsGiveExactlyTheConfiguredError) {
  FaultSchedule f(R"([{"type": "bias", "start_s": 498, "end_s": 505, "offset": [0.4, -0.2, 0]},
                      {"type": "drift", "start_s": 500, "end_s": 510, "rate": [0.1, 0, 0]},
                      {"type": "sigma", "start_s": 498, "end_s": 505, "factor": 0.1, "fix_type": 2}])",
                  3, {"bias", "drift", "sigma"});
  Rng rng(1);
  auto e = f.at(497.9, rng);
  EXPECT_EQ(e.offset, (std::vector<double>{0, 0, 0}));
  e = f.at(499, rng);
  EXPECT_DOUBLE_EQ(e.offset[0], 0.4);
  EXPECT_DOUBLE_EQ(e.offset[1], -0.2);
  EXPECT_DOUBLE_EQ(e.sigma_factor, 0.1);
  EXPECT_EQ(e.fix_type, 2);
  e = f.at(503, rng);
  EXPECT_DOUBLE_EQ(e.offset[0], 0.4 + 0.1 * 3);
  e = f.at(507, rng);
  EXPECT_DOUBLE_EQ(e.offset[0], 0.1 * 7);
  EXPECT_FALSE(e.fix_type);
  e = f.at(510, rng);
  EXPECT_DOUBLE_EQ(e.offset[0], 0.0);
}

TEST(Faults, ErrorsNameTheJsonPointer) {
  auto msg = [](const std::string& j) {
    try {
      FaultSchedule(j, 3, {"bias", "noise"});
    } catch (const FaultError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(msg(R"([{"type": "bias", "start_s": 1, "end_s": 2, "offset": [1, 2]}])"),
            "/0/offset: must be an array of 3 numbers");
  EXPECT_EQ(msg(R"([{"type": "noise", "start_s": 1, "end_s": 2, "factor": 2}, {"type": "freeze", "start_s": 1, "end_s": 2}])"),
            "/1/type: 'freeze' is not one of: bias, noise");
  EXPECT_EQ(msg(R"([{"type": "noise", "start_s": 1, "end_s": 2, "factr": 2}])"), "/0/factr: unknown key");
}

TEST(Referee, DetectsAWallContactAndCountsLaps) {
  WorldSpec w;
  w.line = oval();
  w.walls.right = true;
  Track t(w);
  Referee r(t, Footprint{3.9, 1.0, 0.97});  // the AV-21's rectangle around the rear axle
  // Drive the centre line twice round at 50 m/s, then drift into the right wall.
  const double v = 50, dt = 0.01;
  double s = 0, time = 0;
  int laps = 0;
  while (s < 2 * t.length() + 10) {
    Frenet f = t.at(s, 0);
    Eigen::Vector2d p = t.position(f);
    auto ev = r.update({time, p.x(), p.y(), t.heading(f), v});
    laps += ev.lap_completed;
    EXPECT_FALSE(ev.wall_contact);
    s += v * dt;
    time += dt;
  }
  EXPECT_EQ(laps, 2);
  ASSERT_EQ(r.lap_times().size(), 2u);
  EXPECT_NEAR(r.lap_times()[0], t.length() / v, 0.02);
  // The corners of a 4.9 m car on a 200 m radius stick out a little: 0.15 m allowance.
  EXPECT_NEAR(r.min_wall_clearance(), 7.5 - 0.97, 0.15);
  bool contact = false;
  for (double d = 0; d > -8 && !contact; d -= 0.1) {
    Frenet f = t.at(s, d);
    Eigen::Vector2d p = t.position(f);
    contact = r.update({time, p.x(), p.y(), t.heading(f), v}).wall_contact;
    time += dt;
  }
  EXPECT_TRUE(contact);
  EXPECT_EQ(r.wall_contacts(), 1);
  EXPECT_LE(r.min_wall_clearance(), 0);
  // Where along the track the least clearance was: where the car drifted into the wall.
  EXPECT_NEAR(r.min_wall_clearance_s(), std::fmod(s, t.length()), 5.0);
  // Localization error against the truth interpolated at the estimate's time: 2 m off the car.
  Frenet f = t.at(s, -0.1);
  Eigen::Vector2d p = t.position(f);
  r.update({time, p.x(), p.y(), t.heading(f), v});
  EXPECT_TRUE(r.localization(time, p.x() + 2.0, p.y()));
  EXPECT_FALSE(r.localization(time + 1.0, p.x(), p.y()));  // no truth yet for that time
  EXPECT_NEAR(r.localization_rmse(), 2.0, 1e-9);
  EXPECT_NEAR(r.localization_max_error(), 2.0, 1e-9);
}

// The perception scorer's geometry and bookkeeping on the oval: the car on the straight at
// d = 2 (left), the outer wall on the right at the edge (d = -7.5).
TEST(PerceptionScore, WallTruthFalseObstaclesAndPylonRange) {
  WorldSpec w;
  w.line = oval();
  w.walls.right = true;
  w.pylons = {Pylon{300, 0, 0.2, 0.7}};
  Track t(w);
  const Eigen::Isometry3d body = pose_on(t, 100, 2.0);
  EXPECT_NEAR(wall_y_in_body(t, body, -1), -9.5, 1e-6);
  EXPECT_TRUE(std::isnan(wall_y_in_body(t, body, +1)));  // no left wall
  const Eigen::Vector3d pylon = pylon_in_body(t, body, 0);
  EXPECT_NEAR(pylon.x(), 200, 1e-6);
  EXPECT_NEAR(pylon.y(), -2, 1e-6);
  PerceptionScore s(t, PerceptionScoreParams{});
  EXPECT_FALSE(s.wall(5, -9.5, true));  // no truth yet: not scored
  // The car drives up to the pylon; the detector sees it from 120 m on, misses it once at 150 m.
  for (int k = 0; k <= 19; ++k) {
    const double at = 100 + 10 * k;  // pylon 200 - 10 k ahead
    const Eigen::Isometry3d b = pose_on(t, at, 2.0);
    const std::int64_t stamp = k * 100'000'000;
    s.truth(stamp, b);
    ASSERT_TRUE(s.wall(stamp + 1, -9.5 + (k == 3 ? 0.2 : 0.0), true));
    const double ahead = 200 - 10 * k;
    std::vector<Eigen::Vector2d> seen;
    if (ahead <= 120 || ahead == 170) seen.emplace_back(ahead + 0.3, -2.2);
    if (k == 7) seen.emplace_back(50, 5);  // nothing there
    ASSERT_TRUE(s.obstacles(stamp + 1, seen));
  }
  EXPECT_EQ(s.wall_frames(), 20u);
  EXPECT_NEAR(PerceptionScore::percentile(s.wall_errors(), 0.5), 0.0, 1e-6);
  EXPECT_NEAR(PerceptionScore::percentile(s.wall_errors(), 1.0), 0.2, 1e-6);
  EXPECT_EQ(s.false_obstacles(), 1u);
  ASSERT_EQ(s.pylon_ranges().size(), 1u);
  EXPECT_NEAR(s.pylon_ranges()[0], std::hypot(120, 2), 1e-6);  // 170 m was a lucky frame, 160 m was missed
}

TEST(LocalizationScore, FlagTimesAndFalseAlarms) {
  brickyard::sim::ScoreParams p;
  p.windows = {{10, 12}};
  p.warmup_s = 1;
  brickyard::sim::LocalizationScore s(p);
  for (int i = 0; i <= 2000; ++i) s.truth(i * 0.01, i * 0.01, 0);
  s.estimate(5.0, 5.0, 0.3, 1);   // an alarm outside the window: false alarm
  s.estimate(6.0, 6.0, 0.0, 0);
  s.estimate(10.2, 10.2, 2.0, 0);  // NORMAL with 2 m error
  s.estimate(10.4, 10.4, 0.0, 2);  // flagged and EMERGENCY 0.4 s in
  EXPECT_EQ(s.false_alarms(), 1);
  EXPECT_NEAR(s.time_to_flag(), 0.4, 1e-9);
  EXPECT_NEAR(s.time_to_emergency(), 0.4, 1e-9);
  EXPECT_NEAR(s.max_error_normal(), 2.0, 1e-12);
  EXPECT_NEAR(s.max_error(), 2.0, 1e-12);
  EXPECT_NEAR(s.p99_error(), 2.0, 1e-12) << "3 samples: the 99th percentile is the largest";
  brickyard::sim::LocalizationScore many(p);
  for (int i = 0; i <= 2000; ++i) many.truth(i * 0.01, i * 0.01, 0);
  for (int i = 0; i < 200; ++i) many.estimate(2 + i * 0.01, 2 + i * 0.01, i < 198 ? 0.1 : 5.0, 0);
  EXPECT_NEAR(many.p99_error(), 0.1, 1e-12) << "2 outliers in 200 are the top 1 %";
  EXPECT_NEAR(many.max_error(), 5.0, 1e-12);
}

// An estimate judged by its own covariance: an honest one's errors sit within it, a confident
// wrong one is counted, and its error is the largest "sure" error.
TEST(LocalizationScore, JudgesAnEstimateByItsOwnCovariance) {
  brickyard::sim::ScoreParams p;
  p.warmup_s = 0;
  brickyard::sim::LocalizationScore s(p);
  for (int i = 0; i <= 1000; ++i) s.truth(i * 0.01, i * 0.01, 0);
  const brickyard::sim::PlanarSpread wide{1.0, 0, 1.0}, narrow_x{0.01, 0, 4.0}, sure{0.04, 0, 0.04};
  s.estimate(1.0, 1.0, 1.5, 0, &wide);       // 1.5 sigma: honest
  s.estimate(2.0, 2.0, 1.5, 0, &narrow_x);   // 0.75 sigma along y, where it is unsure: honest
  s.estimate(3.0, 3.3, 0.0, 0, &narrow_x);   // 3 sigma along x: NEES 9, still within 99.9 %
  s.estimate(4.0, 4.6, 0.0, 0, &sure);       // sure to 0.2 m and 0.6 m off: NEES 9
  s.estimate(5.0, 5.0, 1.0, 0, &sure);       // 5 sigma: NEES 25, confidently wrong
  const brickyard::sim::PlanarSpread flat{1.0, 1.0, 1.0};
  s.estimate(6.0, 6.0, 0.0, 0, &flat);       // not positive definite: scored, not judged
  s.estimate(7.0, 7.0, 0.0, 0);              // no spread: scored, not judged
  EXPECT_EQ(s.samples(), 7u);
  EXPECT_EQ(s.judged(), 5u);
  EXPECT_NEAR(s.overconfident_share(), 0.2, 1e-12);
  EXPECT_NEAR(s.nees_p99(), 25.0, 1e-9);
  EXPECT_NEAR(s.max_error_sure(), 1.0, 1e-12) << "the narrow-in-x estimate is not sure along y";
  brickyard::sim::LocalizationScore none(p);
  EXPECT_TRUE(std::isnan(none.overconfident_share()));
  EXPECT_TRUE(std::isnan(none.nees_p99()));
}

// The samples file names what was scored against what, and only a finished log has the name
// asked for: a run that dies leaves none, and a folder that cannot be written is named.
TEST(SampleLog, WritesTheFileOnlyWhenFinished) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("brickyard_samples_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "s.csv").string();
  {
    brickyard::sim::LocalizationScore score{brickyard::sim::ScoreParams{}};
    for (int i = 0; i <= 10; ++i) score.truth(i, i, 0);
    ASSERT_TRUE(score.estimate(2.5, 2.5, 0.3, 1));
    brickyard::sim::SampleLog log(path);
    const auto [tx, ty] = score.last_truth();
    log.add({2.5, 2.5, 0.3, 0.0, 0.01, 0, 0.04, 0.0001, 1, 4, tx, ty});
    EXPECT_FALSE(fs::exists(path)) << "not finished yet";
    log.finish();
  }
  std::ifstream f(path);
  std::string header, row;
  std::getline(f, header);
  std::getline(f, row);
  EXPECT_EQ(header, "t,x,y,yaw,cov_xx,cov_xy,cov_yy,var_yaw,status,update_case,truth_x,truth_y,error_m");
  EXPECT_EQ(row, "2.5000,2.5000,0.3000,0.00000,0.01,0,0.04,0.0001,1,4,2.5000,0.0000,0.3000");
  { brickyard::sim::SampleLog dies((dir / "dies.csv").string()); }
  EXPECT_FALSE(fs::exists(dir / "dies.csv"));
  EXPECT_FALSE(fs::exists(dir / "dies.csv.part"));
  try {
    brickyard::sim::SampleLog nowhere((dir / "missing" / "s.csv").string());
    ADD_FAILURE() << "a folder that does not exist was written";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing/s.csv"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// The car's side of the command contract: the newest command holds while commands keep coming;
// 0.25 s without one, the throttle is released and the car brakes, steering held; commands that
// come back take over again; a stack that never sends one is caught after first_timeout_s.
TEST(CommandWatchdog, BrakesToAStopWhenCommandsStopAndHandsBackWhenTheyCome) {
  CommandWatchdog w;
  Command drive;
  drive.steer = 0.05, drive.throttle = 0.8;
  double t = 0;
  for (; t < 1.0; t += 0.002) EXPECT_DOUBLE_EQ(w.apply(t, std::fmod(t, 0.01) < 0.002, drive).throttle, 0.8);
  EXPECT_FALSE(w.stopping());
  Command c;
  for (double end = t + 0.24; t < end; t += 0.002) c = w.apply(t, false, drive);
  EXPECT_DOUBLE_EQ(c.throttle, 0.8) << "0.24 s without a command: still the stack's";
  for (double end = t + 0.05; t < end; t += 0.002) c = w.apply(t, false, drive);
  EXPECT_TRUE(w.stopping());
  EXPECT_DOUBLE_EQ(c.throttle, 0);
  EXPECT_DOUBLE_EQ(c.brake, CommandWatchdogParams{}.brake);
  EXPECT_DOUBLE_EQ(c.steer, 0.05);
  const double silent_since = t - 0.24 - 0.05;
  c = w.apply(t, true, drive);
  EXPECT_FALSE(w.stopping());
  EXPECT_DOUBLE_EQ(c.throttle, 0.8);
  EXPECT_EQ(w.trips(), 1);
  EXPECT_NEAR(w.longest_gap(t), t - silent_since, 0.011) << "the gap the stack was gone for";
  const double last = t;
  EXPECT_DOUBLE_EQ(w.last_command(), last);
  for (double end = t + 3; t < end; t += 0.002) c = w.apply(t, false, drive);
  EXPECT_NEAR(w.longest_gap(t), t - last, 1e-9) << "a stack gone for good: the gap still open counts";
  EXPECT_DOUBLE_EQ(w.last_command(), last);
  CommandWatchdog never;
  EXPECT_FALSE(never.stopping());
  for (t = 10; t < 11.9; t += 0.01) EXPECT_DOUBLE_EQ(never.apply(t, false, Command{}).brake, 0.0);
  for (; t < 12.1; t += 0.01) never.apply(t, false, Command{});
  EXPECT_TRUE(never.stopping());
  EXPECT_DOUBLE_EQ(never.quiet_since(), 10.0);  // its first step: the warning's "for 2 s", not since the epoch
}

namespace {

// The notices of one kind, in order.
std::vector<RefereeNotice> of_kind(const std::vector<RefereeNotice>& all, RefereeNotice::Kind kind) {
  std::vector<RefereeNotice> out;
  for (const auto& n : all)
    if (n.kind == kind) out.push_back(n);
  return out;
}

// The car on the oval's centre line (or `d` off it) at s, heading along the track.
TruthSample on_oval(const Track& t, double time, double s, double d, double speed) {
  Frenet f = t.at(s, d);
  Eigen::Vector2d p = t.position(f);
  return {time, p.x(), p.y(), t.heading(f), speed};
}

}  // namespace

// A one-lap race: the progress fields every 100 samples and at the line, the lap's log line, and
// the finish once the laps are done.
TEST(RaceJudge, ProgressLapLineAndFinish) {
  WorldSpec w;
  w.line = oval();
  Track t(w);
  RaceRules rules;
  rules.laps = 1;
  RaceJudge judge(t, Footprint{3.9, 1.0, 0.97}, rules);
  const double v = 50, dt = 0.01;
  std::vector<RefereeNotice> all;
  int i = 0;
  for (double s = 0; s < t.length() + 10; s += v * dt, ++i) {
    auto said = judge.update(on_oval(t, i * dt, s, 0, v));
    if (i == 99) {  // the 100th sample: the progress line
      ASSERT_EQ(said.size(), 2u);
      EXPECT_EQ(said[0].field, "speed");
      EXPECT_EQ(said[0].text, "50.0 m/s");
      EXPECT_EQ(said[1].field, "lap");
      EXPECT_EQ(said[1].text, "1/1");
    }
    all.insert(all.end(), said.begin(), said.end());
  }
  const auto statuses = of_kind(all, RefereeNotice::Kind::status);
  EXPECT_GE(statuses.size(), 2u * (i / 100));
  EXPECT_EQ(statuses.back().text, "2/1");  // the lap done: the progress line says so at once
  const auto info = of_kind(all, RefereeNotice::Kind::info);
  ASSERT_EQ(info.size(), 1u);
  EXPECT_EQ(info[0].text.rfind("lap 1: ", 0), 0u) << info[0].text;
  const auto finish = of_kind(all, RefereeNotice::Kind::finish);
  ASSERT_EQ(finish.size(), 1u);
  EXPECT_EQ(finish[0].text, "1 laps completed");
  EXPECT_TRUE(of_kind(all, RefereeNotice::Kind::fail).empty());
  EXPECT_TRUE(judge.run_ended().empty());
  EXPECT_FALSE(judge.failed());
}

// A car that stops short of its laps fails the run once, at the timeout; the end of the run then
// says nothing more.
TEST(RaceJudge, AStoppedCarDidNotFinishOnce) {
  WorldSpec w;
  w.line = oval();
  Track t(w);
  RaceRules rules;
  rules.laps = 2;
  rules.stopped_timeout_s = 10;
  RaceJudge judge(t, Footprint{3.9, 1.0, 0.97}, rules);
  std::vector<RefereeNotice> fails;
  for (int i = 0; i <= 1200; ++i) {
    const double time = i * 0.01;
    const bool moving = i <= 100;
    auto said = judge.update(on_oval(t, time, moving ? 10 * time : 10.0, 0, moving ? 10.0 : 0.0));
    for (const auto& n : of_kind(said, RefereeNotice::Kind::fail)) fails.push_back(n);
  }
  ASSERT_EQ(fails.size(), 1u);
  EXPECT_EQ(fails[0].text, "did not finish: 0 of 2 laps; the car stopped at s = 10.0 m and stood 10.0 s");
  EXPECT_TRUE(judge.failed());
  EXPECT_TRUE(judge.run_ended().empty());
}

// A pylon passed nearer than required fails the run once, however much nearer the car comes.
TEST(RaceJudge, AClosePassFailsTheRunOnce) {
  WorldSpec w;
  w.line = oval();
  w.pylons = {Pylon{300, 0, 0.2, 0.7}};
  Track t(w);
  RaceRules rules;
  rules.obstacle_clearance_required = 2.0;
  RaceJudge judge(t, Footprint{3.9, 1.0, 0.97}, rules);
  std::vector<RefereeNotice> fails;
  int i = 0;
  for (double s = 200; s < 400; s += 0.5, ++i) {
    auto said = judge.update(on_oval(t, i * 0.01, s, -2.0, 50));
    for (const auto& n : of_kind(said, RefereeNotice::Kind::fail)) fails.push_back(n);
  }
  ASSERT_EQ(fails.size(), 1u);
  EXPECT_EQ(fails[0].text.rfind("obstacle passed 1.", 0), 0u) << fails[0].text;  // as soon as it is under 2 m
  EXPECT_NE(fails[0].text.find("(at least 2.00 m required)"), std::string::npos) << fails[0].text;
  EXPECT_NEAR(judge.referee().obstacle_min_clearance(), 2.0 - 0.97 - 0.2, 1e-6);
  EXPECT_EQ(judge.referee().obstacles_hit(), 0);
}

// A wall contact is a crash that fails the run, or with crash_ends_run off a warning; a race that
// ends short of its laps (and has not failed already) did not finish.
TEST(RaceJudge, WallContactAndARaceCutShort) {
  WorldSpec w;
  w.line = oval();
  w.walls.right = true;
  Track t(w);
  for (bool crash_ends_run : {true, false}) {
    RaceRules rules;
    rules.laps = 3;
    rules.crash_ends_run = crash_ends_run;
    RaceJudge judge(t, Footprint{3.9, 1.0, 0.97}, rules);
    const auto said = judge.update(on_oval(t, 0.0, 50, -7.5, 50));
    const std::string contact = "wall contact at s = 50.0 m, t = 0.000 s, 50.0 m/s";
    const auto fails = of_kind(said, RefereeNotice::Kind::fail);
    const auto end = judge.run_ended();
    if (crash_ends_run) {
      ASSERT_EQ(fails.size(), 1u);
      EXPECT_EQ(fails[0].text, "crash: " + contact);
      EXPECT_TRUE(end.empty());
    } else {
      EXPECT_TRUE(fails.empty());
      const auto warnings = of_kind(said, RefereeNotice::Kind::warn);
      ASSERT_FALSE(warnings.empty());
      EXPECT_EQ(warnings.back().text, contact);
      ASSERT_EQ(end.size(), 1u);
      EXPECT_EQ(end[0].kind, RefereeNotice::Kind::fail);
      EXPECT_EQ(end[0].text, "did not finish: 0 of 3 laps; the run ended at t = 0.0 s with the car at s = 50.0 m");
    }
  }
  EXPECT_FALSE(RaceJudge::world_never_seen(0));
  EXPECT_EQ(RaceJudge::world_never_seen(2).value_or(""), "did not finish: 0 of 2 laps; the referee never saw the world");
}

TEST(Scanner, PlacedSpecInRadiansAndRows) {
  LidarRowsDeg rows;
  rows.h_fov_deg = 90;
  rows.rows = 4;
  rows.row_spacing = "uniform";
  const LidarSpec s = placed_spec(LidarSpec{}, {1, 2, 3}, {0, 90, 180}, rows);
  EXPECT_EQ(s.mount, Eigen::Vector3d(1, 2, 3));
  EXPECT_DOUBLE_EQ(s.roll, 0);
  EXPECT_DOUBLE_EQ(s.pitch, M_PI / 2);
  EXPECT_DOUBLE_EQ(s.yaw, M_PI);
  EXPECT_DOUBLE_EQ(s.h_fov, M_PI / 2);
  EXPECT_EQ(s.elevations, row_elevations(4, -15, 15, "uniform", 2.0));
  rows.row_angles_deg = {-10, 0, 10};  // explicit rows override the rest
  const LidarSpec e = placed_spec(LidarSpec{}, {0, 0, 0}, {0, 0, 0}, rows);
  ASSERT_EQ(e.elevations.size(), 3u);
  EXPECT_DOUBLE_EQ(e.elevations[0], -10 * M_PI / 180);
  EXPECT_DOUBLE_EQ(e.elevations[1], 0.0);
  EXPECT_DOUBLE_EQ(e.elevations[2], 10 * M_PI / 180);
}

// The fault windows over the frames: a freeze repeats the last fresh frame (a fresh one when there
// is none yet), a dropout loses the frame; what is returned is counted and digested.
TEST(Scanner, FaultWindowsOverFrames) {
  WorldSpec w;
  w.line = oval();
  w.walls.left = w.walls.right = true;
  const Track t(w);
  LidarRowsDeg rows;
  rows.row_angles_deg = {0.0};
  LidarSpec spec;
  spec.columns = 8;
  spec = placed_spec(spec, {0, 0, 0.5}, {0, 0, 0}, rows);
  const std::string faults = R"([{"type": "freeze", "start_s": 0, "end_s": 1}, {"type": "dropout", "start_s": 2, "end_s": 3},
                                 {"type": "freeze", "start_s": 4, "end_s": 5}])";
  auto scanner = [&] {
    Scanner s(spec, FaultSchedule(faults, 1, kLidarFaultTypes), Rng(7));
    s.start(w);
    return s;
  };
  Scanner s = scanner();
  EXPECT_TRUE(s.started());
  const Eigen::Isometry3d pose = pose_on(t, 400, 0);
  const double x = pose.translation().x(), y = pose.translation().y();
  ASSERT_EQ(s.frame(0.5, pose, x, y), Scanner::Frame::fresh);  // frozen, but nothing to repeat yet
  const std::size_t n1 = s.points().x.size();
  EXPECT_GT(n1, 0u);
  EXPECT_LE(n1, 8u);
  ASSERT_EQ(s.frame(1.5, pose, x, y), Scanner::Frame::fresh);
  const std::size_t n2 = s.points().x.size();
  EXPECT_EQ(s.frame(2.5, pose, x, y), Scanner::Frame::lost);
  EXPECT_EQ(s.frame(4.5, pose, x, y), Scanner::Frame::repeat);
  EXPECT_EQ(s.frames(), 2u);
  EXPECT_EQ(s.frames_lost(), 1u);
  EXPECT_GT(s.rays(), 0u);
  EXPECT_DOUBLE_EQ(s.points_per_frame(), static_cast<double>(n1 + n2) / 2);
  EXPECT_NE(s.digest(), Digest{}.hex());
  Scanner again = scanner();  // the same seed and frames: the same points
  again.frame(0.5, pose, x, y);
  again.frame(1.5, pose, x, y);
  EXPECT_EQ(again.digest(), s.digest());
}

// The car placed on the road reports its truth at base_link where it was placed; it rolls on
// along the centre line; a state that is no longer finite stops the run.
TEST(CarOnTrack, PlacedRollsOnAndRefusesANonFiniteState) {
  WorldSpec w;
  w.line = oval();
  const Track t(w);
  CarOnTrack car(av21_vehicle());
  EXPECT_FALSE(car.placed());
  car.place(t, 100, 1.0, 20);
  EXPECT_TRUE(car.placed());
  const Frenet f = t.at(100, 1.0);
  BaseLinkTruth b = car.truth();
  EXPECT_NEAR(b.x, t.position(f).x(), 1e-9);
  EXPECT_NEAR(b.y, t.position(f).y(), 1e-9);
  EXPECT_NEAR(b.yaw, t.heading(f), 1e-12);
  EXPECT_NEAR(b.z, t.road_z(f), 1e-9);
  EXPECT_NEAR(b.s, 100, 1e-6);
  EXPECT_NEAR(b.d, 1.0, 1e-6);
  EXPECT_DOUBLE_EQ(b.vx, 20);
  for (int i = 0; i < 100; ++i) car.step(0.002, Command{});  // 0.2 s coasting
  b = car.truth();
  EXPECT_NEAR(b.s, 104, 0.1);
  EXPECT_NEAR(b.d, 1.0, 1e-6);
  EXPECT_LT(b.vx, 20);
  Command broken;
  broken.throttle = std::nan("");
  EXPECT_THROW(car.step(0.002, broken), std::runtime_error);
}

// The watchdog's warnings: when it takes over from a silent stack, and when the stack is back.
TEST(CarOnTrack, WatchdogWarnsWhenItTakesOverAndHandsBack) {
  CommandWatchdog dog;
  Command drive;
  drive.throttle = 0.8;
  WatchedCommand c = watch_command(dog, 0.0, true, drive);
  EXPECT_TRUE(c.warning.empty());
  EXPECT_DOUBLE_EQ(c.command.throttle, 0.8);
  c = watch_command(dog, 0.3, false, drive);
  EXPECT_EQ(c.warning, "no command for 0.300000 s: throttle off, braking to a stop");
  EXPECT_DOUBLE_EQ(c.command.throttle, 0);
  EXPECT_DOUBLE_EQ(c.command.brake, CommandWatchdogParams{}.brake);
  c = watch_command(dog, 0.4, false, drive);
  EXPECT_TRUE(c.warning.empty()) << "said once";
  c = watch_command(dog, 0.5, true, drive);
  EXPECT_EQ(c.warning, "commands again: the stack drives (the longest gap between two so far: 0.500000 s)");
  EXPECT_DOUBLE_EQ(c.command.throttle, 0.8);
}

TEST(DriverLine, LimitsFromTheGraphOrTheCar) {
  DriverProfile p;
  p.limits.v_max = 50;
  p.limits.a_lat = 10;
  p.limits.a_accel = 5;
  p.limits.a_decel = 9;
  const auto car = av21_vehicle();
  const auto graph = profile_limits(p, car);
  EXPECT_DOUBLE_EQ(graph.v_max, 50);
  EXPECT_DOUBLE_EQ(graph.a_lat, 10);
  EXPECT_DOUBLE_EQ(graph.a_accel, 5);
  EXPECT_DOUBLE_EQ(graph.a_decel, 9);
  EXPECT_FALSE(graph.ellipse);
  p.vehicle_limits = true;
  p.grip_use = 0.9;
  const auto own = profile_limits(p, car);
  const auto file = brickyard::motion::vehicle_limits(car);
  EXPECT_DOUBLE_EQ(own.a_lat, file.a_lat * 0.9);
  EXPECT_DOUBLE_EQ(own.v_max, file.v_max);
  EXPECT_EQ(own.ellipse, file.ellipse);
}

TEST(DriverLine, PlannedLapOfASquareAtConstantSpeed) {
  brickyard::motion::RacingLine r;
  r.x = {0, 10, 10, 0};
  r.y = {0, 0, 10, 10};
  r.speed = {5, 5, 5, 5};
  EXPECT_NEAR(planned_lap_s(r), 40.0 / 5, 1e-12);
}

// A line 7 m left of the centre of a 15 m wide road is pulled in to 2.5 m from the edge when the
// track is known; without it, it is the file's.
TEST(DriverLine, KeptInsideTheTrackWhenThereIsOne) {
  WorldSpec w;
  w.line = oval();
  const Track t(w);
  CenterLine xy;
  for (double s = 0; s < t.length() - 2.5; s += 5) {
    const Eigen::Vector2d p = t.position(t.at(s, 7.0));
    xy.x.push_back(p.x());
    xy.y.push_back(p.y());
  }
  const DriverProfile p;
  const auto limits = profile_limits(p, av21_vehicle());
  const DriverLine free = driver_line(xy, nullptr, p, limits);
  EXPECT_EQ(free.line.x, xy.x);
  EXPECT_DOUBLE_EQ(free.planned_lap_s, planned_lap_s(free.line));
  const DriverLine kept = driver_line(xy, &t, p, limits);
  const auto expected = brickyard::motion::make_racing_line(brickyard::motion::keep_inside(xy, t, 2.5), limits, 30);
  EXPECT_EQ(kept.line.x, expected.x);
  EXPECT_EQ(kept.line.y, expected.y);
  EXPECT_DOUBLE_EQ(kept.planned_lap_s, planned_lap_s(expected));
  for (std::size_t i = 0; i < kept.line.x.size(); ++i) EXPECT_LE(t.project(kept.line.x[i], kept.line.y[i]).d, 5.0 + 0.05) << i;
}

// A rival's driver (issue 46): its line moved 3 m left of the file's, its speeds 80 % of the
// profile's, its lap planned 1 / 0.8 as long.
TEST(DriverLine, ARivalsLineMovedAcrossAndItsPaceScaled) {
  WorldSpec w;
  w.line = oval();
  const Track t(w);
  CenterLine xy;
  for (double s = 0; s < t.length() - 2.5; s += 5) {
    const Eigen::Vector2d p = t.position(t.at(s, 0.0));
    xy.x.push_back(p.x());
    xy.y.push_back(p.y());
  }
  DriverProfile p;
  const auto limits = profile_limits(p, av21_vehicle());
  const DriverLine own = driver_line(xy, nullptr, p, limits);
  p.lateral_offset = 3.0;
  p.speed_scale = 0.8;
  const DriverLine rival = driver_line(xy, nullptr, p, limits);
  for (std::size_t i = 0; i < rival.line.x.size(); ++i) EXPECT_NEAR(t.project(rival.line.x[i], rival.line.y[i]).d, 3.0, 0.05) << i;
  double worst = 0;
  const DriverLine moved = driver_line(moved_across(xy, 3.0), nullptr, DriverProfile{}, limits);
  for (std::size_t i = 0; i < rival.line.speed.size(); ++i) worst = std::max(worst, std::abs(rival.line.speed[i] - 0.8 * moved.line.speed[i]));
  EXPECT_LT(worst, 1e-9);
  EXPECT_NEAR(rival.planned_lap_s, moved.planned_lap_s / 0.8, 1e-6);
  EXPECT_GT(rival.planned_lap_s, own.planned_lap_s);
}

// Two cars' plan-view rectangles (4.9 m long from 1.7 m behind the rear axle, 1.9 m wide): nose to
// tail 1 m apart, side by side 1.5 m apart, touching, and at an angle (a corner the nearest).
TEST(CarContacts, TouchAndGapOfTwoCars) {
  const Footprint fp{3.2, 1.7, 0.95};
  const CarBox ours{0, 0, 0, fp};
  EXPECT_NEAR(car_gap(ours, {3.2 + 1.0 + 1.7, 0, 0, fp}), 1.0, 1e-12) << "nose to tail";
  EXPECT_NEAR(car_gap(ours, {0.5, 1.9 + 1.5, 0, fp}), 1.5, 1e-12) << "side by side";
  EXPECT_TRUE(cars_touch(ours, {4.8, 0.3, 0.1, fp}));
  EXPECT_EQ(car_gap(ours, {4.8, 0.3, 0.1, fp}), 0.0);
  EXPECT_FALSE(cars_touch(ours, {3.2 + 1.7 + 0.01, 0, 0, fp})) << "1 cm apart";
  // Turned 90 degrees ahead: its nearest point is its side's, 0.95 m from its centre line.
  const CarBox across{3.2 + 2.0 + 0.95, -0.75, M_PI / 2, fp};
  EXPECT_NEAR(car_gap(ours, across), 2.0, 1e-12);
  EXPECT_EQ(car_gap(ours, across), car_gap(across, ours));
}

// A contact counted once while two cars touch, again when they touch anew; the least gap kept.
TEST(CarContacts, AContactIsCountedOnceWhileTheCarsTouch) {
  const Footprint fp{3.2, 1.7, 0.95};
  CarContactBook book;
  const CarBox ours{0, 0, 0, fp};
  EXPECT_TRUE(book.update(ours, {std::nullopt, CarBox{20, 0, 0, fp}}).empty());
  EXPECT_NEAR(book.min_gap(), 20 - 3.2 - 1.7, 1e-12);
  EXPECT_EQ(book.update(ours, {std::nullopt, CarBox{4.5, 0, 0, fp}}), std::vector<int>{1});
  EXPECT_TRUE(book.update(ours, {std::nullopt, CarBox{4.6, 0, 0, fp}}).empty()) << "still touching";
  EXPECT_TRUE(book.update(ours, {std::nullopt, CarBox{6, 0, 0, fp}}).empty());
  EXPECT_EQ(book.update(ours, {CarBox{0, 1.5, 0, fp}, CarBox{6, 0, 0, fp}}), std::vector<int>{0});
  EXPECT_EQ(book.contacts(), 2);
  EXPECT_EQ(book.min_gap(), 0.0);
}

TEST(WorldBuilder, WallsOnTheirSides) {
  const CenterLine line = oval();  // counter-clockwise: its outside is on the right
  WallSettings s;
  Walls w = place_walls(line, s);
  EXPECT_TRUE(w.right);
  EXPECT_FALSE(w.left);
  EXPECT_DOUBLE_EQ(w.right_offset, 0.0);
  EXPECT_DOUBLE_EQ(w.left_offset, 2.0);
  EXPECT_DOUBLE_EQ(w.height, 1.2);
  s.outer_side = "left";
  s.inner_wall = true;
  s.wall_height_m = 2;
  w = place_walls(line, s);
  EXPECT_TRUE(w.left);
  EXPECT_TRUE(w.right);
  EXPECT_DOUBLE_EQ(w.left_offset, 0.0);
  EXPECT_DOUBLE_EQ(w.right_offset, 2.0);
  EXPECT_DOUBLE_EQ(w.height, 2.0);
}

TEST(WorldBuilder, PylonListAndItsErrors) {
  const auto pylons = parse_pylons(R"([{"s": 10, "d": 1}, {"s": 20, "d": -1, "radius": 0.3, "height": 1}])");
  ASSERT_EQ(pylons.size(), 2u);
  EXPECT_DOUBLE_EQ(pylons[0].s, 10);
  EXPECT_DOUBLE_EQ(pylons[0].radius, 0.2);
  EXPECT_DOUBLE_EQ(pylons[0].height, 0.7);
  EXPECT_DOUBLE_EQ(pylons[1].radius, 0.3);
  auto error = [](const std::string& j) {
    try {
      parse_pylons(j);
    } catch (const WorldError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("{}"), "parameter 'pylons': must be an array");
  EXPECT_EQ(error("[1]"), "parameter 'pylons' /0: must be an object {s, d, radius, height}");
  EXPECT_EQ(error(R"([{"s": 1, "d": "x"}])"), "parameter 'pylons' /0/d: must be a number");
  EXPECT_EQ(error(R"([{"s": 1, "d": 0, "r": 1}])"), "parameter 'pylons' /0/r: unknown key (s, d, radius, height)");
  EXPECT_EQ(error(R"([{"s": 1, "d": 0}, {"s": 1}])"), "parameter 'pylons' /1: needs s and d");
  EXPECT_EQ(error(R"([{"s": 1, "d": 0, "radius": 0}])"), "parameter 'pylons' /0: radius and height must be positive");
}

TEST(WorldBuilder, BuildsTheWorldAndFindsPylonsOffTheRoad) {
  BankSpec bank = default_bank();
  const WorldSpec w = build_world(oval(), "oval", bank, WallSettings{}, R"([{"s": 100, "d": 0}, {"s": 200, "d": 9}])");
  EXPECT_EQ(w.name, "oval");
  EXPECT_EQ(w.bank.size(), w.line.x.size());
  EXPECT_TRUE(w.walls.right);
  ASSERT_EQ(w.pylons.size(), 2u);
  const Track t(w);
  const auto off = pylons_off_road(t);
  ASSERT_EQ(off.size(), 1u);
  EXPECT_DOUBLE_EQ(off[0].s, 200);
  bank.mode = "sideways";
  try {
    build_world(oval(), "oval", bank, WallSettings{}, "[]");
    ADD_FAILURE() << "an unknown bank mode was taken";
  } catch (const WorldError& e) {
    EXPECT_EQ(std::string(e.what()), "parameter 'bank_mode': unknown bank mode 'sideways'");
  }
}

TEST(GnssReceiver, CarriedTruthAndTheBodyPose) {
  BodyState s;
  s.yaw = M_PI / 2;
  s.vx = 10;
  s.yaw_rate = 0.1;
  const BodyState at = carried(s, 0.002);
  EXPECT_NEAR(at.x, 0.0, 1e-12);
  EXPECT_NEAR(at.y, 0.02, 1e-12);
  EXPECT_NEAR(at.yaw, M_PI / 2 + 0.0002, 1e-12);
  BodyState p;
  p.x = 1, p.y = 2, p.z = 3, p.yaw = M_PI / 2;
  const Eigen::Vector3d q = world_from_body(p) * Eigen::Vector3d(1, 0, 0);
  EXPECT_NEAR(q.x(), 1, 1e-12);
  EXPECT_NEAR(q.y(), 3, 1e-12);
  EXPECT_NEAR(q.z(), 3, 1e-12);
}

// Without noise a fix is the antenna's position, carried to the fix's stamp; the fault windows
// drop, freeze (once there is a fix) and bias fixes.
TEST(GnssReceiver, AntennaPositionAndFaultWindows) {
  GnssNoise noise;
  noise.sigma_m = noise.sigma_z_m = 0;
  noise.reported_sigma_m = 0.02;
  const std::string faults = R"([{"type": "freeze", "start_s": 0, "end_s": 1}, {"type": "dropout", "start_s": 2, "end_s": 3},
                                 {"type": "freeze", "start_s": 4, "end_s": 5},
                                 {"type": "bias", "start_s": 6, "end_s": 7, "offset": [1, 0, 0], "fix_type": 1}])";
  GnssReceiver r(Eigen::Vector3d(1, 0.5, 1.2), noise, FaultSchedule(faults, 3, kGnssFaultTypes), Rng(3));
  BodyState truth;
  truth.x = 10, truth.y = 20, truth.vx = 40;
  const std::int64_t ms = 1'000'000;
  ASSERT_EQ(r.epoch(500 * ms, truth, 500 * ms), GnssReceiver::Epoch::fresh);  // frozen, but no fix yet
  EXPECT_NEAR(r.fix().x, 11, 1e-9);
  EXPECT_NEAR(r.fix().y, 20.5, 1e-9);
  EXPECT_NEAR(r.fix().z, 1.2, 1e-9);
  EXPECT_DOUBLE_EQ(r.fix().sigma_x, 0.02);
  EXPECT_DOUBLE_EQ(r.fix().sigma_z, 0.02);
  EXPECT_EQ(r.fix().fix_type, 3);
  EXPECT_TRUE(r.fix().valid);
  ASSERT_EQ(r.epoch(1500 * ms, truth, 1498 * ms), GnssReceiver::Epoch::fresh);  // truth 2 ms old: 8 cm on
  EXPECT_NEAR(r.fix().x, 11.08, 1e-9);
  EXPECT_EQ(r.epoch(2500 * ms, truth, 2500 * ms), GnssReceiver::Epoch::dropped);
  EXPECT_EQ(r.epoch(4500 * ms, truth, 4500 * ms), GnssReceiver::Epoch::frozen);
  EXPECT_NEAR(r.fix().x, 11.08, 1e-9) << "a frozen epoch leaves the last fix";
  ASSERT_EQ(r.epoch(6500 * ms, truth, 6500 * ms), GnssReceiver::Epoch::fresh);
  EXPECT_NEAR(r.fix().x, 12, 1e-9);
  EXPECT_EQ(r.fix().fix_type, 1);
  EXPECT_EQ(r.fixes(), 3u);
}

// Noise is drawn every epoch, so a dropout leaves the fixes after it as they would have been.
TEST(GnssReceiver, ADropoutLeavesTheNoiseSequence) {
  GnssNoise noise;
  const std::string dropout = R"([{"type": "dropout", "start_s": 2, "end_s": 3}])";
  GnssReceiver a(Eigen::Vector3d::Zero(), noise, FaultSchedule(dropout, 3, kGnssFaultTypes), Rng(5));
  GnssReceiver b(Eigen::Vector3d::Zero(), noise, FaultSchedule("[]", 3, kGnssFaultTypes), Rng(5));
  const BodyState truth;
  const std::int64_t ms = 1'000'000;
  for (std::int64_t t : {1000 * ms, 2500 * ms}) {
    a.epoch(t, truth, t);
    b.epoch(t, truth, t);
  }
  ASSERT_EQ(a.epoch(3500 * ms, truth, 3500 * ms), GnssReceiver::Epoch::fresh);
  ASSERT_EQ(b.epoch(3500 * ms, truth, 3500 * ms), GnssReceiver::Epoch::fresh);
  EXPECT_EQ(a.fix().x, b.fix().x);
  EXPECT_EQ(a.fix().z, b.fix().z);
  EXPECT_NE(a.fix().x, 0.0);
  EXPECT_DOUBLE_EQ(a.fix().sigma_x, noise.sigma_m);  // reported: sigma_m
  EXPECT_DOUBLE_EQ(a.fix().sigma_z, noise.sigma_m * (noise.sigma_z_m / noise.sigma_m));
  EXPECT_EQ(a.fixes(), 2u);
  EXPECT_EQ(b.fixes(), 3u);
}

// The real clock's span of a car step: the time since the last, in equal steps of at most the
// period, bounded; a step on time is one step of its own length.
TEST(StepSpan, TheCarKeepsUpWithTheWallAfterAStall) {
  const StepSpan on_time = real_clock_span(0.0021, 0.002);
  EXPECT_EQ(on_time.steps, 2);
  EXPECT_DOUBLE_EQ(on_time.dt, 0.00105);
  const StepSpan exact = real_clock_span(0.002, 0.002);
  EXPECT_EQ(exact.steps, 1);
  EXPECT_DOUBLE_EQ(exact.dt, 0.002);
  const StepSpan stall = real_clock_span(0.15, 0.002);  // 0.15 s without a step: 75 steps
  EXPECT_EQ(stall.steps, 75);
  EXPECT_NEAR(stall.steps * stall.dt, 0.15, 1e-12);
  const StepSpan stopped = real_clock_span(30, 0.002);  // a process stopped for 30 s: 1 s of physics
  EXPECT_NEAR(stopped.steps * stopped.dt, 1.0, 1e-12);
  EXPECT_LE(stopped.dt, 0.002);
  EXPECT_EQ(real_clock_span(-1, 0.002).steps, 1);  // a clock that went back: one step of the period
  EXPECT_DOUBLE_EQ(real_clock_span(-1, 0.002).dt, 0.002);
}
