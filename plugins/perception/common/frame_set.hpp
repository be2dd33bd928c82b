#pragma once
// Merging the car's LiDARs into one frame, framework-free.
//  - SensorPose: a sensor's mount in the vehicle frame (as carried in each PointCloud message;
//    rotation yaw·pitch·roll about z, y, x).
//  - FrameSet: which clouds make one frame. A cloud joins the open set when its stamp lies within
//    `window` of the set's first; the set is complete when every expected sensor has delivered.
//    A cloud outside the window closes the open set as it is (a sensor lost a frame: the others
//    are not held back for ever) and opens the next. A cloud older than the set open or last
//    merged is too late: dropped and counted.
#include "points.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace brickyard::perception {

struct SensorPose {
  double x = 0, y = 0, z = 0, roll = 0, pitch = 0, yaw = 0;
  Eigen::Isometry3f vehicle_from_sensor() const {
    Eigen::Isometry3f t = Eigen::Isometry3f::Identity();
    t.translate(Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)));
    t.rotate(Eigen::AngleAxisf(static_cast<float>(yaw), Eigen::Vector3f::UnitZ()) *
             Eigen::AngleAxisf(static_cast<float>(pitch), Eigen::Vector3f::UnitY()) *
             Eigen::AngleAxisf(static_cast<float>(roll), Eigen::Vector3f::UnitX()));
    return t;
  }
};

// r * (x, y, z) + o, each coordinate summed as Eigen's product sums it (a0 + (a1 + a2)), so the
// same bits: written out because GCC at -O2 called Eigen's assignment loop for every point, its
// operands through the stack (10 % of a race's CPU in the ground filter).
inline Point transformed(const Eigen::Matrix3f& r, const Eigen::Vector3f& o, float x, float y, float z) {
  return {(r(0, 0) * x + (r(0, 1) * y + r(0, 2) * z)) + o.x(), (r(1, 0) * x + (r(1, 1) * y + r(1, 2) * z)) + o.y(),
          (r(2, 0) * x + (r(2, 1) * y + r(2, 2) * z)) + o.z()};
}

// Leaves a point where it is (append_in_vehicle_frame's default).
struct KeepPoint {
  Point operator()(std::size_t, const Point& p) const { return p; }
};

// Appends n sensor-frame points to `out` in the vehicle frame, each then through move(i, p)
// (deskew.hpp moves them to the frame's stamp); points not finite or beyond kMaxCoordinate once
// moved are skipped.
template <class Move = KeepPoint>
inline void append_in_vehicle_frame(const SensorPose& pose, const float* x, const float* y, const float* z, std::size_t n,
                                    Points& out, Move move = {}) {
  const Eigen::Isometry3f t = pose.vehicle_from_sensor();
  const Eigen::Matrix3f r = t.linear();
  const Eigen::Vector3f o = t.translation();
  // Written in place and cut to what was kept (a push_back's capacity check per point cost as
  // much as the transform).
  const std::size_t at = out.size();
  out.resize(at + n);
  Point* dst = out.data() + at;
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Point p = move(i, transformed(r, o, x[i], y[i], z[i]));
    dst[m] = p;
    m += in_range(p);
  }
  out.resize(at + m);
}

template <class Cloud> class FrameSet {
 public:
  FrameSet(int sensors, std::int64_t window_ns) : slots_(sensors), window_(window_ns) {}

  // Offers sensor `s`'s cloud stamped `stamp_ns`. Returns the sets this closes, oldest first
  // (at most two: the open one cut short, and the new one when a single sensor completes it).
  std::vector<std::vector<Cloud>> offer(int s, std::int64_t stamp_ns, Cloud cloud) {
    std::vector<std::vector<Cloud>> done;
    if (stamp_ns < last_closed_ns_ || (open_ && stamp_ns < first_ns_)) {  // older than what was merged: too late
      ++late_;
      return done;
    }
    if (open_ && (stamp_ns - first_ns_ >= window_ || slots_[s])) {
      done.push_back(close());
      ++partial_;
    }
    if (!open_) {
      open_ = true;
      first_ns_ = stamp_ns;
    }
    slots_[s] = std::move(cloud);
    if (std::all_of(slots_.begin(), slots_.end(), [](const auto& c) { return c.has_value(); })) done.push_back(close());
    return done;
  }
  std::uint64_t partial() const { return partial_; }
  std::uint64_t late() const { return late_; }

 private:
  std::vector<Cloud> close() {
    std::vector<Cloud> set;
    for (auto& c : slots_)
      if (c) set.push_back(std::move(*c)), c.reset();
    open_ = false;
    last_closed_ns_ = first_ns_;
    return set;
  }
  std::vector<std::optional<Cloud>> slots_;
  std::int64_t window_, first_ns_ = 0, last_closed_ns_ = std::numeric_limits<std::int64_t>::min();
  bool open_ = false;
  std::uint64_t partial_ = 0, late_ = 0;
};

}  // namespace brickyard::perception
