#pragma once
// The obstacle detector's frames of clusters matched with the wall fits of the same stamp from the
// right and the left wall detector, framework-free: the obstacles then do not depend on which
// detector the executive steps first. Frame and Wall are what the caller keeps of each (its
// messages); a stamp is the frame's, in ns.
#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

namespace brickyard::perception {

template <class Frame, class Wall> class StampMatch {
 public:
  static constexpr std::size_t kWallsKept = 16;  // per side: the latest fits
  static constexpr std::size_t kMaxWaiting = 3;  // frames waiting for a fit: more, and the oldest goes without it

  // `wired`: whether a wall detector feeds side 0 (right) and side 1 (left).
  explicit StampMatch(std::array<bool, 2> wired = {false, false}) : wired_(wired) {}

  void add_frame(std::int64_t stamp, Frame f) { frames_.emplace_back(stamp, std::move(f)); }
  void add_wall(int side, std::int64_t stamp, Wall w) {
    walls_[side].emplace_back(stamp, std::move(w));
    if (walls_[side].size() > kWallsKept) walls_[side].pop_front();
  }

  struct Match {
    Frame frame;
    std::vector<std::pair<Wall, int>> walls;  // the fits of its stamp with their side: -1 right, then +1 left
  };
  // The oldest frame with the fits of its stamp, once every wired side has its fit or a later one
  // (then this frame has none of that side); a detector that stopped answering must not hold the
  // obstacles back for long: with more than kMaxWaiting frames waiting the oldest goes without its
  // fit (counted: unmatched()). Nothing while the oldest waits.
  std::optional<Match> next() {
    if (frames_.empty()) return std::nullopt;
    const std::int64_t t = frames_.front().first;
    std::vector<std::pair<Wall, int>> walls;
    bool wait = false;
    for (int s = 0; s < 2; ++s) {
      if (!wired_[s]) continue;
      const Wall* same = nullptr;
      bool newer = false;
      for (const auto& [stamp, w] : walls_[s]) {
        if (stamp == t) same = &w;
        newer = newer || stamp > t;
      }
      if (same) walls.emplace_back(*same, s == 0 ? -1 : 1);
      else if (!newer) wait = true;  // the fit of this frame is still to come
    }
    if (wait && frames_.size() <= kMaxWaiting) return std::nullopt;
    if (wait) ++unmatched_;
    Match m{std::move(frames_.front().second), std::move(walls)};
    frames_.pop_front();
    return m;
  }

  std::size_t waiting() const { return frames_.size(); }
  std::uint64_t unmatched() const { return unmatched_; }

 private:
  std::array<bool, 2> wired_;
  std::deque<std::pair<std::int64_t, Frame>> frames_;
  std::array<std::deque<std::pair<std::int64_t, Wall>>, 2> walls_;
  std::uint64_t unmatched_ = 0;
};

}  // namespace brickyard::perception
