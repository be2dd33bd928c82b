// Planning algorithms on synthetic tracks with known answers.
#include "common/min_curvature.hpp"
#include "common/min_time.hpp"
#include "common/speed_profile.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace brickyard::planning;

namespace {

// A ring of radius r (counter-clockwise), `half` m to each edge, a point every ~5 m.
ClosedLine ring(double r, double half) {
  ClosedLine c;
  const int n = static_cast<int>(2 * M_PI * r / 5);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    c.x.push_back(r * std::cos(a));
    c.y.push_back(r * std::sin(a));
    c.width_left.push_back(half);
    c.width_right.push_back(half);
  }
  return c;
}

// An oval: two 500 m straights and two 150 m half circles, 7.5 m to each edge.
ClosedLine oval() {
  ClosedLine c;
  auto add = [&](double x, double y) {
    c.x.push_back(x);
    c.y.push_back(y);
    c.width_left.push_back(7.5);
    c.width_right.push_back(7.5);
  };
  const double L = 500, r = 150;
  for (double s = 0; s < L; s += 5) add(s, 0);
  for (int i = 0; i < static_cast<int>(M_PI * r / 5); ++i) {
    const double a = -M_PI / 2 + M_PI * i / static_cast<int>(M_PI * r / 5);
    add(L + r * std::cos(a), r + r * std::sin(a));
  }
  for (double s = 0; s < L; s += 5) add(L - s, 2 * r);
  for (int i = 0; i < static_cast<int>(M_PI * r / 5); ++i) {
    const double a = M_PI / 2 + M_PI * i / static_cast<int>(M_PI * r / 5);
    add(r * std::cos(a), r + r * std::sin(a));
  }
  return c;
}

// The simulator's AV-21, as bench/eval_racing_line.cpp compares the lines.
VehicleLimits av21() {
  VehicleLimits l;
  l.v_max = 90;
  l.a_lat = 15;
  l.a_accel = 9000.0 / 815;
  l.a_decel = 15;
  l.power = 370e3 / 815;
  l.drag = 1.2 * 0.85 / (2 * 815);
  return l;
}

}  // namespace

// On a ring the least curvature is the widest circle: the line hugs the outside (the right of a
// counter-clockwise ring) at the margin.
TEST(MinCurvature, ARingIsDrivenOnTheOutside) {
  const ClosedLine c = ring(200, 7.5);
  MinCurvatureParams p;
  const MinCurvatureResult r = min_curvature_line(c, p);
  for (double a : r.offset) EXPECT_NEAR(a, -(7.5 - p.margin), 1e-6);
  EXPECT_LT(summed_squared_curvature(r.x, r.y), summed_squared_curvature(c.x, c.y));
}

// On an oval it stays within the width and bends less than the centre line. (Two straights 300 m
// apart joined by half circles: the best a line can do is a larger half circle, R 156 m instead
// of 150 — about 8 % less squared curvature in the turns.)
TEST(MinCurvature, AnOvalBendsLessWithinTheWidth) {
  const ClosedLine c = oval();
  MinCurvatureParams p;
  const MinCurvatureResult r = min_curvature_line(c, p);
  double lo = 0, hi = 0;
  for (double a : r.offset) {
    EXPECT_GE(a, -(7.5 - p.margin) - 1e-9);
    EXPECT_LE(a, 7.5 - p.margin + 1e-9);
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  // Outside - apex - outside: the outside edge before and after each bend, the inside at its apex.
  EXPECT_NEAR(lo, -(7.5 - p.margin), 1e-6);
  EXPECT_NEAR(hi, 7.5 - p.margin, 1e-6);
  const double ours = summed_squared_curvature(r.x, r.y), centre = summed_squared_curvature(c.x, c.y);
  EXPECT_LT(ours, 0.92 * centre);
  EXPECT_GE(r.iterations, 1);
  EXPECT_LE(r.iterations, p.max_iterations);
}

TEST(MinCurvature, BadInputIsRefused) {
  ClosedLine c = ring(100, 5);
  c.width_left.pop_back();
  EXPECT_THROW(min_curvature_line(c), std::invalid_argument);
}

// The reverse-accumulated lap-time derivatives against central differences of the whole lap,
// along a smooth change of the curvatures and of the steps (away from the ellipse's corner).
TEST(MinTime, LapTimeGradientMatchesDifferences) {
  const ClosedLine c = oval();
  const int n = static_cast<int>(c.x.size());
  std::vector<double> ds(n), k(n), dk, dds;
  for (int i = 0; i < n; ++i) ds[i] = std::hypot(c.x[(i + 1) % n] - c.x[i], c.y[(i + 1) % n] - c.y[i]);
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n, b = (i + 1) % n;
    const double ux = c.x[i] - c.x[a], uy = c.y[i] - c.y[a], vx = c.x[b] - c.x[i], vy = c.y[b] - c.y[i];
    k[i] = 2 * (ux * vy - uy * vx) / (std::hypot(ux, uy) * std::hypot(vx, vy) * std::hypot(c.x[b] - c.x[a], c.y[b] - c.y[a]));
  }
  const VehicleLimits l = av21();
  const double t = closed_lap_time_gradient(ds, k, l, dk, dds);
  EXPECT_DOUBLE_EQ(t, profile_time(ds, speed_profile(ds, k, l, true), true));
  for (int which = 0; which < 2; ++which) {
    std::vector<double> w(n);
    double predicted = 0;
    for (int i = 0; i < n; ++i) {
      // (Not antisymmetric under the oval's half turn, or the two halves' effects would cancel.)
      w[i] = (1 + 0.5 * std::sin(4 * M_PI * i / n + 0.3)) * (which == 0 ? 1e-4 : 1e-2);  // curvature 1/m, or step m
      predicted += w[i] * (which == 0 ? dk[i] : dds[i]);
    }
    auto lap = [&](double e) {
      std::vector<double> d2 = ds, k2 = k;
      for (int i = 0; i < n; ++i) (which == 0 ? k2[i] : d2[i]) += e * w[i];
      return profile_time(d2, speed_profile(d2, k2, l, true), true);
    };
    const double e = 1e-3, measured = (lap(e) - lap(-e)) / (2 * e);
    EXPECT_NEAR(predicted, measured, 0.02 * std::abs(measured) + 1e-9) << (which == 0 ? "curvature" : "steps");
    EXPECT_GT(std::abs(measured), 1e-6);
  }
}

// From the minimum-curvature line on the oval: a faster lap (never a slower one), every offset in
// the box, the bending energy within the slack, and the same answer twice.
TEST(MinTime, FasterInsideTheBoxWithinTheSlack) {
  const ClosedLine c = oval();
  const MinCurvatureResult mc = min_curvature_line(c);
  const VehicleLimits l = av21();
  for (double slack : {0.0, 0.003, 0.05}) {
    MinTimeParams p;
    p.curvature_slack = slack;
    const MinTimeResult r = min_time_refine(c, mc.offset, l, p);
    EXPECT_DOUBLE_EQ(r.start_time, lap_time(mc.x, mc.y, l));
    EXPECT_DOUBLE_EQ(r.time, lap_time(r.x, r.y, l));
    EXPECT_DOUBLE_EQ(r.energy, summed_squared_curvature(r.x, r.y));
    // With no slack the minimum-curvature optimum has little to give; with some, time is bought.
    if (slack == 0) EXPECT_LE(r.time, r.start_time);
    else EXPECT_LT(r.time, r.start_time - 0.005) << "slack " << slack;
    EXPECT_LE(r.energy, r.start_energy * (1 + slack)) << "slack " << slack;
    for (double a : r.offset) {
      EXPECT_GE(a, -(7.5 - p.margin) - 1e-12);
      EXPECT_LE(a, 7.5 - p.margin + 1e-12);
    }
    const MinTimeResult again = min_time_refine(c, mc.offset, l, p);
    EXPECT_EQ(again.offset, r.offset);
    EXPECT_EQ(again.time, r.time);
    EXPECT_EQ(again.iterations, r.iterations);
  }
}

// A known answer: on a ring where the car never reaches its cornering limit (v_max 20 m/s on
// R ≈ 200 m), the shortest way round is the fastest — the inside edge, opposite the
// minimum-curvature line's outside. With room in the slack (Σ κ² ds = 2π/R rises 6 % from
// R 206 m to 194 m) the whole line moves inside; with 2 % it goes as far in as the slack lets it,
// R = 206 / 1.02; starting on the inside it has nothing to gain and stays.
TEST(MinTime, OnASlowRingTheShortestLineWins) {
  const ClosedLine c = ring(200, 7.5);
  VehicleLimits l;
  l.v_max = 20;
  const MinCurvatureResult mc = min_curvature_line(c);
  MinTimeParams p;
  p.curvature_slack = 0.1;
  const MinTimeResult in = min_time_refine(c, mc.offset, l, p);
  for (double a : in.offset) EXPECT_NEAR(a, 6.0, 1e-3);
  EXPECT_NEAR(in.time, in.start_time * 194.0 / 206.0, 0.01);
  p.curvature_slack = 0.02;
  const MinTimeResult part = min_time_refine(c, mc.offset, l, p);
  EXPECT_LE(part.energy, 1.02 * part.start_energy);
  EXPECT_LT(part.time, part.start_time);
  for (double a : part.offset) EXPECT_NEAR(a, 200 - 206 / 1.02, 0.05);
  const MinTimeResult stay = min_time_refine(c, in.offset, l, p);
  EXPECT_EQ(stay.time, stay.start_time);
  EXPECT_EQ(stay.offset, in.offset);
}

TEST(MinTime, BadInputIsRefused) {
  const ClosedLine c = ring(100, 5);
  const VehicleLimits l;
  EXPECT_THROW(min_time_refine(c, std::vector<double>(3, 0.0), l), std::invalid_argument);
  MinTimeParams p;
  p.curvature_slack = -0.01;
  EXPECT_THROW(min_time_refine(c, {}, l, p), std::invalid_argument);
  p = {};
  p.smoothing = 0;
  EXPECT_THROW(min_time_refine(c, {}, l, p), std::invalid_argument);
  ClosedLine bad = c;
  bad.width_right.pop_back();
  EXPECT_THROW(min_time_refine(bad, {}, l), std::invalid_argument);
}
