#include "stop_line.hpp"

#include "track/curvature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brickyard::vehicle_interface {
namespace {

using Points = std::vector<control::PathPoint>;

struct Across {
  double along = 0;              // m covered from the trip's point
  double d = 0;                  // m left of the centre line
  double left = 0, right = 0;    // the edges: d of the left one, minus d of the right one
  Eigen::Vector2d normal{0, 0};  // the centre line's left normal there
};

double step_length(const Points& p, std::size_t i) { return std::hypot(p[i].x - p[i - 1].x, p[i].y - p[i - 1].y); }

// A racing line is a loop (its ends as near as its points: the path tracker's test); a planner's
// path over a horizon is open.
bool closed(const Points& path) {
  if (path.size() < 3) return false;
  double longest = 0;
  for (std::size_t i = 1; i < path.size(); ++i) longest = std::max(longest, step_length(path, i));
  return std::hypot(path.front().x - path.back().x, path.front().y - path.back().y) <= 2 * longest;
}

std::vector<Across> place_on_track(const Points& line, const track::Track& track) {
  std::vector<Across> out;
  int hint = -1;
  double along = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (i > 0) along += step_length(line, i);
    const track::Frenet f = track.project(line[i].x, line[i].y, hint);
    hint = f.seg;
    out.push_back({along, f.d, track.width_left(f.seg, f.u), track.width_right(f.seg, f.u), track.segments()[f.seg].n});
  }
  return out;
}

// How far each point moves (left positive) to keep the room; 0 where the edges do not bracket it.
std::vector<double> moves_for_room(const std::vector<Across>& line, const StopLineParams& p) {
  std::vector<double> move(line.size(), 0.0);
  if (line.empty()) return move;
  const auto room_of = [](const Across& a) { return std::min(a.left - a.d, a.d + a.right); };
  const double start = std::clamp(room_of(line.front()), 0.0, p.edge_room_m);
  const double growth = std::tan(p.heading_doubt_deg * M_PI / 180);
  for (std::size_t i = 0; i < line.size(); ++i) {
    const Across& a = line[i];
    if (!(room_of(a) >= 0)) continue;  // off the map's edges (or no number): not the map's to say
    const double grown = a.along < p.onset_m ? 0.5 * a.along * a.along / p.onset_m : a.along - 0.5 * p.onset_m;
    const double room = start + growth * grown;
    const double lo = -a.right + room, hi = a.left - room;
    move[i] = (lo > hi ? 0.5 * (a.left - a.right) : std::clamp(a.d, lo, hi)) - a.d;
    if (!std::isfinite(move[i])) move[i] = 0;
  }
  return move;
}

// Each move averaged over the points within a quarter of the smoothing length either side, twice
// (a triangle's weights over smoothing_m): a kink where the room starts to bite becomes a bend.
// Before the trip the moves are taken as none (points every metre or as the path's first), so
// the line leaves the path there smoothly.
std::vector<double> smoothed(const std::vector<double>& move, const std::vector<Across>& line, double length) {
  const double spacing = std::max(line.size() > 1 ? line[1].along : 1.0, 1.0);
  const std::size_t before = static_cast<std::size_t>(std::ceil(0.5 * length / spacing));
  std::vector<double> along(before + line.size()), in(before + line.size(), 0.0), out(in.size());
  for (std::size_t i = 0; i < along.size(); ++i)
    along[i] = i < before ? -spacing * static_cast<double>(before - i) : line[i - before].along;
  std::copy(move.begin(), move.end(), in.begin() + static_cast<std::ptrdiff_t>(before));
  for (int pass = 0; pass < 2; ++pass) {
    std::size_t lo = 0, hi = 0;
    double sum = 0;
    for (std::size_t i = 0; i < in.size(); ++i) {
      while (hi < in.size() && along[hi] <= along[i] + 0.25 * length) sum += in[hi++];
      while (along[lo] < along[i] - 0.25 * length) sum -= in[lo++];
      out[i] = sum / static_cast<double>(hi - lo);
    }
    in.swap(out);
  }
  return {in.begin() + static_cast<std::ptrdiff_t>(before), in.end()};
}

Points moved(Points line, const std::vector<Across>& across, const std::vector<double>& move, double share) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    line[i].x += share * move[i] * across[i].normal.x();
    line[i].y += share * move[i] * across[i].normal.y();
  }
  return line;
}

// Whether `line` asks no more lateral grip than `path` did at the stop's pace, or than braking at
// pace.decel leaves. The stop's speed at each point: braked from the trip at pace.decel, less
// where the path's turn takes the grip (the stop brakes no harder than the friction circle
// leaves), and no more than the path's own speed there (the stop meets those; 0 is none given).
bool drivable(const Points& line, const Points& path, const std::vector<Across>& across, const StopPace& pace) {
  constexpr double kChord = 5, kSlack = 0.5;  // m either side (the tracker's 10 m window); m/s^2 of noise
  const bool gripped = pace.grip > 0;
  const double free = gripped ? std::sqrt(std::max(0.0, pace.grip * pace.grip - pace.decel * pace.decel))
                              : std::numeric_limits<double>::infinity();
  double braked = pace.speed * pace.speed;  // v^2 as braked from the trip
  for (std::size_t i = 0; i < across.size(); ++i) {
    const double path_turn = std::abs(curvature_at(path, i, kChord));
    if (i > 0) {
      const double lateral = braked * path_turn;
      const double decel = gripped ? std::min(pace.decel, std::sqrt(std::max(0.0, pace.grip * pace.grip - lateral * lateral))) : pace.decel;
      braked -= 2 * decel * (across[i].along - across[i - 1].along);
    }
    const double v2 = path[i].speed > 0 ? std::min(braked, path[i].speed * path[i].speed) : braked;
    if (v2 <= 0) break;  // stood before here
    const double asked = v2 * std::abs(curvature_at(line, i, kChord));
    if (!(asked <= std::max(free, v2 * path_turn) + kSlack)) return false;  // (a curvature that is no number: not drivable)
  }
  return true;
}

}  // namespace

double curvature_at(const std::vector<control::PathPoint>& line, std::size_t i, double half) {
  std::size_t lo = i, hi = i;
  double back = 0, ahead = 0;
  while (lo > 0 && back < half) back += step_length(line, lo), --lo;
  while (hi + 1 < line.size() && ahead < half) ahead += step_length(line, hi + 1), ++hi;
  if (!(back >= 0.5 * half && ahead >= 0.5 * half)) return 0;  // near an end, or points on one spot: none to speak of
  return track::menger_curvature(line[lo].x, line[lo].y, line[i].x, line[i].y, line[hi].x, line[hi].y);
}

std::vector<control::PathPoint> stop_line(const std::vector<control::PathPoint>& path, std::size_t from,
                                          const track::Track& track, const StopLineParams& p, const StopPace& pace) {
  if (from >= path.size()) return path;
  // From the trip's point on; a loop goes on round past its end.
  Points ahead(path.begin() + static_cast<std::ptrdiff_t>(from), path.end());
  if (closed(path)) ahead.insert(ahead.end(), path.begin(), path.begin() + static_cast<std::ptrdiff_t>(from));
  const std::vector<Across> across = place_on_track(ahead, track);
  const std::vector<double> move = smoothed(moves_for_room(across, p), across, p.smoothing_m);
  for (double share : {1.0, 0.5, 0.25}) {
    Points line = moved(ahead, across, move, share);
    if (!drivable(line, ahead, across, pace)) continue;
    if (closed(path)) return line;  // (the loop begins at the trip's point now)
    line.insert(line.begin(), path.begin(), path.begin() + static_cast<std::ptrdiff_t>(from));
    return line;
  }
  return path;
}

}  // namespace brickyard::vehicle_interface
