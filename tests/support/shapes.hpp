#pragma once
// Synthetic tracks for unit tests: a counter-clockwise circle of radius r in n points, `half` m
// to each edge. Any line type with x, y, width_left and width_right (track::CenterLine,
// planning::ClosedLine).
#include <cmath>

template <class Line> Line circle_line(double r, int n, double half) {
  Line c;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    c.x.push_back(r * std::cos(a));
    c.y.push_back(r * std::sin(a));
    c.width_left.push_back(half);
    c.width_right.push_back(half);
  }
  return c;
}
