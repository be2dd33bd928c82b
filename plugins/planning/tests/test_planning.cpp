// Planning algorithms on synthetic tracks with known answers.
#include "planning/common/min_curvature.hpp"
#include "planning/common/line_setup.hpp"
#include "planning/common/min_time.hpp"
#include "motion/speed_profile.hpp"
#include "motion/vehicle_limits.hpp"
#include "track/curvature.hpp"

#include "av21.hpp"
#include "shapes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace brickyard::planning;

namespace {

// A ring of radius r (counter-clockwise), `half` m to each edge, a point every ~5 m.
ClosedLine ring(double r, double half) { return circle_line<ClosedLine>(r, static_cast<int>(2 * M_PI * r / 5), half); }

// An oval: two straights of L (500 m) and two half circles of radius r (150 m), `half` (7.5 m) to
// each edge, a point every ~5 m.
ClosedLine oval(double r = 150, double L = 500, double half = 7.5) {
  ClosedLine c;
  auto add = [&](double x, double y) {
    c.x.push_back(x);
    c.y.push_back(y);
    c.width_left.push_back(half);
    c.width_right.push_back(half);
  };
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

// An ellipse with semi-axes a (along x) and b, n points, `half` m to each edge.
ClosedLine ellipse(double a, double b, int n, double half) {
  ClosedLine c;
  for (int i = 0; i < n; ++i) {
    c.x.push_back(a * std::cos(2 * M_PI * i / n));
    c.y.push_back(b * std::sin(2 * M_PI * i / n));
    c.width_left.push_back(half);
    c.width_right.push_back(half);
  }
  return c;
}

// The AV-21's limits, as bench/eval_racing_line.cpp compares the lines.
VehicleLimits av21() { return brickyard::motion::vehicle_limits(av21_vehicle()); }

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

// The averaged measure (lap_profile's average_m): its curvature is track::signed_curvature's, the
// Menger curvature averaged over curvature_window points each side; its derivatives by the raw
// curvatures are the averaged measure's mapped back through the same average (its own adjoint).
// Checked against central differences on an ellipse (400 × 150 m: the car is at its cornering
// limit only near the ends, so the derivatives peak there), changing the raw curvature of the
// point where the averaged measure's derivative peaks (the apex at one end), and of the points 5
// and 10 after it.
TEST(MinTime, AveragedLapTimeGradientThroughTheAverage) {
  const int n = 400;  // ≈ 5.4 m apart
  const ClosedLine c = ellipse(400, 150, n, 7.5);
  const VehicleLimits l = av21();
  const LapProfile raw = lap_profile(c.x, c.y, l), avg = lap_profile(c.x, c.y, l, 30);
  const brickyard::track::CenterLine cl{"", c.x, c.y, {}, {}};
  const int half = brickyard::track::curvature_window(cl, 30);
  EXPECT_EQ(half, 3);  // 30 m in steps of about 5.4 m: 3 each side
  EXPECT_EQ(avg.kappa, brickyard::track::signed_curvature(cl, 30));
  EXPECT_EQ(avg.ds, raw.ds);
  EXPECT_EQ(avg.time, profile_time(avg.ds, speed_profile(avg.ds, avg.kappa, l, true), true));
  EXPECT_EQ(raw.time, lap_time(c.x, c.y, l));
  EXPECT_EQ(avg.time, lap_time(c.x, c.y, l, 30));
  EXPECT_LT(avg.time, raw.time);  // the average lowers the peaks of curvature
  const std::vector<double> mean = brickyard::track::cyclic_average(raw.kappa, half);
  for (int i = 0; i < n; ++i) EXPECT_NEAR(mean[i], avg.kappa[i], 1e-15) << i;

  std::vector<double> dk, dds;
  closed_lap_time_gradient(avg.ds, avg.kappa, l, dk, dds);
  const std::vector<double> back = brickyard::track::cyclic_average(dk, half);
  int peak = 0;
  for (int i = 0; i < n; ++i)
    if (std::abs(dk[i]) > std::abs(dk[peak])) peak = i;
  for (int j : {peak, (peak + 5) % n, (peak + 10) % n}) {
    auto lap = [&](double e) {
      std::vector<double> k = raw.kappa;
      k[j] += e;
      const std::vector<double> ka = brickyard::track::cyclic_average(k, half);
      return profile_time(avg.ds, speed_profile(avg.ds, ka, l, true), true);
    };
    const double e = 1e-7, measured = (lap(e) - lap(-e)) / (2 * e);
    EXPECT_GT(std::abs(measured), 1e-3) << j;
    EXPECT_NEAR(back[j], measured, 0.02 * std::abs(measured)) << j;
    // Unmapped, the peak's would be a third too large (elsewhere the derivatives vary slowly).
    if (j == peak) {
      EXPECT_GT(std::abs(dk[j] - measured), 0.2 * std::abs(measured));
    }
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
    EXPECT_DOUBLE_EQ(r.start_averaged_time, lap_time(mc.x, mc.y, l, 30));
    EXPECT_DOUBLE_EQ(r.averaged_time, lap_time(r.x, r.y, l, 30));
    EXPECT_DOUBLE_EQ(r.energy, summed_squared_curvature(r.x, r.y));
    // Neither measure gets worse. With no slack the minimum-curvature optimum has little to give;
    // with some, time is bought under both.
    EXPECT_LE(r.time, r.start_time);
    EXPECT_LE(r.averaged_time, r.start_averaged_time);
    if (slack > 0) {
      EXPECT_LT(r.time, r.start_time - 0.01) << "slack " << slack;
      EXPECT_LT(r.averaged_time, r.start_averaged_time - 0.01) << "slack " << slack;
    }
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

// Both measures in the objective, against the point-wise lap time alone (averaged_over 0, the
// refinement's first form), on an oval with tighter bends (60 m): alone, the point-wise measure
// stalls within a few ms of its start; with the averaged one beside it both measures gain a
// tenth of a second or more. With averaged_over 0 the averaged time is not measured.
TEST(MinTime, TheAveragedMeasureFindsTimeThePointwiseMisses) {
  const ClosedLine c = oval(60);
  const MinCurvatureResult mc = min_curvature_line(c);
  const VehicleLimits l = av21();
  MinTimeParams p;
  const MinTimeResult both = min_time_refine(c, mc.offset, l, p);
  p.averaged_over = 0;
  const MinTimeResult alone = min_time_refine(c, mc.offset, l, p);
  EXPECT_EQ(alone.start_averaged_time, 0);
  EXPECT_EQ(alone.averaged_time, 0);
  EXPECT_LE(alone.time, alone.start_time);
  EXPECT_GT(alone.time, alone.start_time - 0.02);
  EXPECT_LT(both.time, both.start_time - 0.1);
  EXPECT_LT(both.averaged_time, both.start_averaged_time - 0.1);
  EXPECT_LE(both.energy, both.start_energy * (1 + p.curvature_slack));
  EXPECT_LT(both.averaged_time, lap_time(alone.x, alone.y, l, 30) - 0.1);
}

// The acceptance rule: a step is kept only if the sum of the lap times goes down and neither gets
// worse. On these lines and slacks some steps that lower the sum make one measure slightly worse
// (kept, they would end the averaged one 1e-5 to 5e-5 s above its start on the first three, the
// point-wise one 2e-4 s above on the last); the rule refuses them.
TEST(MinTime, NeitherMeasureGetsWorse) {
  struct Case {
    ClosedLine line;
    double slack;
  };
  const std::vector<Case> cases = {{oval(110, 300, 4), 0.0},
                                   {oval(100, 500, 5), 0.0},
                                   {ellipse(300, 100, 260, 7.5), 0.0},
                                   {oval(90, 300, 4), 0.003}};
  const VehicleLimits l = av21();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const MinCurvatureResult mc = min_curvature_line(cases[i].line);
    MinTimeParams p;
    p.curvature_slack = cases[i].slack;
    const MinTimeResult r = min_time_refine(cases[i].line, mc.offset, l, p);
    EXPECT_LE(r.time, r.start_time) << i;
    EXPECT_LE(r.averaged_time, r.start_averaged_time) << i;
    EXPECT_LE(r.energy, r.start_energy * (1 + p.curvature_slack)) << i;
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
  p = {};
  p.averaged_over = -1;
  EXPECT_THROW(min_time_refine(c, {}, l, p), std::invalid_argument);
  p.averaged_over = std::nan("");
  EXPECT_THROW(min_time_refine(c, {}, l, p), std::invalid_argument);
  EXPECT_THROW(lap_profile({0, 1}, {0, 1}, l, 30), std::invalid_argument);
  EXPECT_THROW(lap_time({0, 1, 2}, {0, 1}, l), std::invalid_argument);
  ClosedLine bad = c;
  bad.width_right.pop_back();
  EXPECT_THROW(min_time_refine(bad, {}, l), std::invalid_argument);
}

// A racing line file with a point beyond an edge is refused, naming the point; one inside but
// nearer an edge than the margin is pulled in (TUM's lines pass within 0.6 m of IMS's edges).
TEST(LineSetup, AFileLineThatLeavesTheTrackIsRefused) {
  using brickyard::track::CenterLine;
  const int n = static_cast<int>(2 * M_PI * 200 / 5);
  brickyard::track::TrackGeometry geo;
  geo.line = circle_line<CenterLine>(200, n, 6);
  const brickyard::track::Track track(geo);
  LineSource src;
  src.edge_margin = 2;
  src.file_line = circle_line<CenterLine>(205, n, 0);  // 5 m outside the centre: 1 m within the outer edge
  const auto kept = line_points(src, &track);
  ASSERT_EQ(kept.x.size(), src.file_line.x.size());
  EXPECT_LT(std::hypot(kept.x[0], kept.y[0]), 205 - 0.9);  // pulled in to the margin
  src.file_line.x[10] *= 1.05;  // that point 10 m further out: 9 m beyond the edge
  src.file_line.y[10] *= 1.05;
  try {
    line_points(src, &track);
    FAIL() << "accepted";
  } catch (const LineLeavesTrack& e) {
    EXPECT_NE(std::string(e.what()).find("point 11 "), std::string::npos) << e.what();  // counted from 1
  }
  EXPECT_EQ(line_points(src, nullptr).x.size(), src.file_line.x.size());  // no map: as it is
}
