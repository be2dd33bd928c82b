#pragma once
// Who is ahead, and the passes (issue 46): each car's progress along the track's centre line,
// unwrapped (laps counted), ours against each other car's. A car first seen within half a lap
// ahead of us is ahead; a pass is completed when a car more than `margin` ahead of us comes to be
// more than `margin` behind (passed by: the other way round), so cars running alongside do not
// count passes back and forth. Framework-free; the referee's judge keeps one.
#include "car_contacts.hpp"
#include "track.hpp"

#include <optional>
#include <vector>

namespace brickyard::sim {

class RaceOrder {
 public:
  // `margin`: m of progress a car must be ahead or behind to count as such (a car's length).
  RaceOrder(const Track& track, double margin) : track_(track), margin_(margin) {}

  struct Pass {
    int car = 0;
    bool ours = true;  // we passed the car; false: it passed us
    double t = 0, s = 0;  // when, and our s then
  };
  // Our car and the others (none: not seen yet) at time t: the passes completed now.
  std::vector<Pass> update(double t, const CarBox& ours, const std::vector<std::optional<CarBox>>& others);

  int passes() const { return passes_; }
  int passed_by() const { return passed_by_; }
  // 1 + the cars ahead of us now (alongside: not ahead).
  int position() const;

 private:
  struct Progress {
    bool seen = false;
    double s = 0;  // unwrapped, m
    int hint = -1;
    int side = 0;  // of a rival: +1 ahead of us, -1 behind, 0 alongside (within margin)
  };
  // p's progress moved on to where (x, y) projects, near where it was (or, first, the lap nearest `near`).
  void advance(Progress& p, double x, double y, double near) const;

  const Track& track_;
  double margin_;
  Progress ours_;
  std::vector<Progress> others_;
  int passes_ = 0, passed_by_ = 0;
};

}  // namespace brickyard::sim
