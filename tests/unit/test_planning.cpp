// Planning algorithms on synthetic tracks with known answers.
#include "common/min_curvature.hpp"

#include <gtest/gtest.h>

#include <cmath>

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
