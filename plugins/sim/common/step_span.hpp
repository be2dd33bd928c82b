#pragma once
// How much physics a periodic simulator step covers. On the sim clock, its period, exactly. On
// the real clock, the time since its last step: a starved process skips periods (the executive
// never bursts to catch up), and a car stepped by its period alone would then fall behind the
// wall's time while its sensors stamp by it; a stall of 0.15 s at 80 m/s left the car 12 m behind
// where the wall's time put it, and the fusion refused every fix after (docs/car-on-wires.md).
// The span is cut into equal steps of at most the period, and bounded (a process stopped for
// longer than `max_s` is not flung along the track). Framework-free.
#include <algorithm>
#include <cmath>

namespace brickyard::sim {

struct StepSpan {
  int steps = 1;
  double dt = 0;  // each
};

inline StepSpan real_clock_span(double elapsed_s, double period_s, double max_s = 1.0) {
  const double span = std::clamp(elapsed_s, 0.0, max_s);
  if (!(span > period_s)) return {1, span > 0 ? span : period_s};
  const int steps = static_cast<int>(std::ceil(span / period_s - 1e-9));
  return {steps, span / steps};
}

}  // namespace brickyard::sim
