#include "perception/common/object_tracker.hpp"
#include "perception/common/car_parts.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <tuple>

namespace brickyard::perception {

double Track::heading() const { return speed() > 1e-9 ? std::atan2(velocity.y(), velocity.x()) : 0.0; }

void ObjectTracker::update(double t, const EgoPose& ego, const std::vector<Detection>& detections) {
  if (started_ && t > t_) predict(t - t_);
  t_ = t;
  started_ = true;
  // Each detection (a car's parts made whole) on the track, with its spread (farther: fewer
  // points, a coarser centroid); those not well inside the road left out.
  const double c = std::cos(ego.yaw), s = std::sin(ego.yaw);
  std::vector<Detection> whole;
  if (p_.whole_cars) {
    std::vector<PriorHeading> prior;  // each detection's heading, less ours
    for (const Detection& d : detections) {
      const track::Frenet f = track_->project(ego.x + c * d.x - s * d.y, ego.y + s * d.x + c * d.y, hint_);
      const auto course = course_across(f);
      prior.push_back({std::remainder(track_->heading(f) + course.value_or(0.0) - ego.yaw, 2 * M_PI), course.has_value()});
    }
    whole = whole_cars(detections, prior, p_.car);
  }
  const std::vector<Detection>& on_road = p_.whole_cars ? whole : detections;
  std::vector<Eigen::Vector2d> z;
  std::vector<double> r;
  std::vector<Detection> kept;
  for (const Detection& d : on_road) {
    const track::Frenet f = track_->project(ego.x + c * d.x - s * d.y, ego.y + s * d.x + c * d.y, hint_);
    hint_ = f.seg;
    if (f.d > track_->width_left(f.seg, f.u) - p_.road_margin || f.d < p_.road_margin - track_->width_right(f.seg, f.u)) {
      ++off_road_;
      continue;
    }
    z.emplace_back(f.s, f.d);
    r.push_back(p_.meas_sigma + p_.meas_sigma_per_m * std::hypot(d.x, d.y));
    kept.push_back(d);
  }
  const std::vector<int> pair = associate(z, r);
  std::vector<bool> hit(tracks_.size(), false);
  for (std::size_t k = 0; k < z.size(); ++k)
    if (pair[k] >= 0) {
      correct(tracks_[pair[k]], z[k], r[k]);
      tracks_[pair[k]].size_x = kept[k].size_x, tracks_[pair[k]].size_y = kept[k].size_y;
      hit[pair[k]] = true;
    }
  age_and_prune(hit);
  for (std::size_t k = 0; k < z.size(); ++k)
    if (pair[k] < 0) birth(z[k], r[k], kept[k]);
  for (Track& tr : tracks_) to_map(tr);
}

// A car on its line runs across the track as well as along it (up to 7 degrees off the centre
// line's heading entering and leaving turns: its back 2.45 m from its centre then puts that 0.3 m
// across); the track nearest the place, moving and sure of its course, says by how much: the
// angle of its velocity to the track's direction. None: along the track.
std::optional<double> ObjectTracker::course_across(const track::Frenet& f) const {
  const Track* nearest = nullptr;
  double best = kCourseRadius;
  for (const Track& tr : tracks_) {
    const double ds = std::remainder(tr.state(0) - f.s, track_->length()), gap = std::hypot(ds, tr.state(1) - f.d);
    if (gap < best) best = gap, nearest = &tr;
  }
  // A young track's velocity is a guess; one whose course is known to a degree or so speaks.
  if (!nearest || !nearest->confirmed || std::abs(nearest->state(2)) < kCourseMinSpeed ||
      std::sqrt(nearest->cov(3, 3)) > kCourseSpread * std::abs(nearest->state(2)))
    return std::nullopt;
  return std::atan2(nearest->state(3), nearest->state(2));
}

namespace {

// The steady model over dt: constant velocity, its acceleration state held at 0; white
// accelerations along and across.
void steady_model(double dt, double along, double across, Track::Mat& F, Track::Mat& Q) {
  F = Track::Mat::Identity();
  F(0, 2) = F(1, 3) = dt;
  F(4, 4) = 0;
  const double dt2 = dt * dt, q[2] = {along * along, across * across};
  Q = Track::Mat::Zero();
  for (int i = 0; i < 2; ++i) {
    Q(i, i) = q[i] * dt2 * dt2 / 4;
    Q(i, i + 2) = Q(i + 2, i) = q[i] * dt2 * dt / 2;
    Q(i + 2, i + 2) = q[i] * dt2;
  }
  Q(4, 4) = 1e-4;  // a spread on the held acceleration keeps the covariance positive
}

}  // namespace

void maneuver_model(double dt, double jerk, double across, Track::Mat& F, Track::Mat& Q) {
  F = Track::Mat::Identity();
  F(0, 2) = F(1, 3) = F(2, 4) = dt;
  F(0, 4) = dt * dt / 2;
  const double t2 = dt * dt, t3 = t2 * dt, t4 = t3 * dt, t5 = t4 * dt, j = jerk * jerk, a = across * across;
  const int along[3] = {0, 2, 4};
  const double G[3][3] = {{t5 / 20, t4 / 8, t3 / 6}, {t4 / 8, t3 / 3, t2 / 2}, {t3 / 6, t2 / 2, dt}};
  Q = Track::Mat::Zero();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Q(along[r], along[c]) = j * G[r][c];
  Q(1, 1) = a * t4 / 4, Q(1, 3) = Q(3, 1) = a * t3 / 2, Q(3, 3) = a * t2;
}

void ObjectTracker::predict(double dt) {
  Track::Mat F[2], Q[2];
  steady_model(dt, p_.accel_sigma, p_.lateral_accel_sigma, F[0], Q[0]);
  maneuver_model(dt, p_.jerk_sigma, p_.maneuver_lateral_sigma, F[1], Q[1]);
  Eigen::Matrix2d P;  // P(i, j): from model i to model j in a frame
  P << 1 - p_.switch_to_maneuver, p_.switch_to_maneuver, p_.switch_to_steady, 1 - p_.switch_to_steady;
  for (Track& tr : tracks_) {
    // IMM's mixing: each model starts from the models' estimates weighed by the chance it came from each.
    const Eigen::Vector2d c = P.transpose() * tr.mode;  // each model's prior probability
    Track::Vec x0[2];
    Track::Mat P0[2];
    for (int j = 0; j < 2; ++j) weighed(tr, Eigen::Vector2d(P(0, j) * tr.mode[0], P(1, j) * tr.mode[1]) / c[j], x0[j], P0[j]);
    for (int j = 0; j < 2; ++j) {
      tr.model_state[j] = F[j] * x0[j];
      tr.model_state[j][0] = track_->wrap_s(tr.model_state[j][0]);
      tr.model_cov[j] = F[j] * P0[j] * F[j].transpose() + Q[j];
    }
    tr.mode = c;
    mix(tr);
  }
}

void ObjectTracker::weighed(const Track& tr, const Eigen::Vector2d& w, Track::Vec& x, Track::Mat& P) const {
  const double L = track_->length();
  x.setZero();
  for (int i = 0; i < 2; ++i) {
    Track::Vec xi = tr.model_state[i];
    xi[0] = tr.model_state[0][0] + std::remainder(xi[0] - tr.model_state[0][0], L);
    x += w[i] * xi;
  }
  P.setZero();
  for (int i = 0; i < 2; ++i) {
    Track::Vec e = tr.model_state[i] - x;
    e[0] = std::remainder(e[0], L);
    P += w[i] * (tr.model_cov[i] + e * e.transpose());
  }
}

void ObjectTracker::mix(Track& tr) const {
  weighed(tr, tr.mode, tr.state, tr.cov);
  tr.state[0] = track_->wrap_s(tr.state[0]);
}

Eigen::Vector2d ObjectTracker::innovation(const Eigen::Vector2d& z, const Track::Vec& x) const {
  Eigen::Vector2d v = z - x.head<2>();
  v[0] = std::remainder(v[0], track_->length());
  return v;
}

std::vector<int> ObjectTracker::associate(const std::vector<Eigen::Vector2d>& z, const std::vector<double>& r) const {
  // Every gated (detection, track) pair by its Mahalanobis distance; taken cheapest first, each
  // detection and track once: a greedy global nearest neighbour (cars on a track are metres
  // apart; the gate keeps two from trading tracks unless they are within a spread of each other).
  std::vector<std::tuple<double, int, int>> pairs;
  for (std::size_t k = 0; k < z.size(); ++k)
    for (std::size_t j = 0; j < tracks_.size(); ++j) {
      const Eigen::Vector2d v = innovation(z[k], tracks_[j].state);
      const Eigen::Matrix2d S = tracks_[j].cov.topLeftCorner<2, 2>() + Eigen::Matrix2d::Identity() * r[k] * r[k];
      const double d2 = v.dot(S.ldlt().solve(v));
      if (d2 <= p_.gate) pairs.emplace_back(d2, static_cast<int>(k), static_cast<int>(j));
    }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> pair(z.size(), -1);
  std::vector<bool> taken(tracks_.size(), false);
  for (const auto& [d2, k, j] : pairs)
    if (pair[k] < 0 && !taken[j]) pair[k] = j, taken[j] = true;
  return pair;
}

void ObjectTracker::correct(Track& tr, const Eigen::Vector2d& z, double r) {
  Eigen::Matrix<double, 2, 5> H = Eigen::Matrix<double, 2, 5>::Zero();
  H(0, 0) = H(1, 1) = 1;
  const Eigen::Matrix2d R = Eigen::Matrix2d::Identity() * r * r;
  Eigen::Vector2d likelihood;
  for (int j = 0; j < 2; ++j) {
    Track::Mat& C = tr.model_cov[j];
    const Eigen::Matrix2d S = H * C * H.transpose() + R;
    const Eigen::Vector2d v = innovation(z, tr.model_state[j]);
    const Eigen::Matrix<double, 5, 2> K = C * H.transpose() * S.inverse();
    tr.model_state[j] += K * v;
    tr.model_state[j][0] = track_->wrap_s(tr.model_state[j][0]);
    // Joseph form: the covariance stays symmetric and positive over thousands of frames.
    const Track::Mat I_KH = Track::Mat::Identity() - K * H;
    C = I_KH * C * I_KH.transpose() + K * R * K.transpose();
    likelihood[j] = std::exp(-0.5 * v.dot(S.ldlt().solve(v))) / (2 * M_PI * std::sqrt(S.determinant()));
  }
  const Eigen::Vector2d w = tr.mode.cwiseProduct(likelihood);
  // Both models far off (a detection at the gate's edge): keep the weights rather than divide by ~0.
  if (w.sum() > 1e-300) tr.mode = w / w.sum();
  tr.mode = tr.mode.cwiseMax(1e-6) / tr.mode.cwiseMax(1e-6).sum();
  mix(tr);
}

void ObjectTracker::age_and_prune(const std::vector<bool>& hit) {
  for (std::size_t j = 0; j < tracks_.size(); ++j) {
    Track& tr = tracks_[j];
    ++tr.age;
    if (hit[j]) ++tr.hits, tr.misses = 0;
    else ++tr.misses;
    // Frames 0 to age seen: within its first confirm_window while age < confirm_window.
    if (!tr.confirmed && tr.age < p_.confirm_window && tr.hits >= p_.confirm_hits) tr.confirmed = true;
  }
  // A tentative track that can no longer reach confirm_hits within its first confirm_window
  // frames dies; a confirmed one coasts max_misses frames.
  const auto dead = [&](const Track& tr) {
    const double spread = std::sqrt(std::max(tr.cov(0, 0), tr.cov(1, 1)));
    const int left = p_.confirm_window - tr.age;  // frames it may still be hit in
    const bool hopeless = !tr.confirmed && tr.hits + std::max(left, 0) < p_.confirm_hits;
    return (tr.confirmed ? tr.misses > p_.max_misses : hopeless || left <= 0) || spread > p_.max_sigma;
  };
  const auto before = tracks_.size();
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(), dead), tracks_.end());
  deaths_ += before - tracks_.size();
}

void ObjectTracker::birth(const Eigen::Vector2d& z, double r, const Detection& d) {
  Track tr;
  tr.id = next_id_++;
  tr.state << z.x(), z.y(), 0, 0, 0;
  const double v2 = p_.birth_speed_sigma * p_.birth_speed_sigma;
  tr.cov = (Track::Vec() << r * r, r * r, v2, v2, 25.0).finished().asDiagonal();  // 5 m/s^2: its acceleration unknown
  for (int j = 0; j < 2; ++j) tr.model_state[j] = tr.state, tr.model_cov[j] = tr.cov;
  tr.size_x = d.size_x, tr.size_y = d.size_y;
  tr.hits = 1;
  tr.confirmed = p_.confirm_hits <= 1;
  tracks_.push_back(tr);
  ++births_;
}

void ObjectTracker::to_map(Track& tr) const {
  // The map frame's position, and its velocity as the motion over a short step along (s, d): the
  // track's curvature included (at d off the centre line, ds/dt is not the car's speed).
  constexpr double kStep = 0.05;  // s
  const auto at = [&](double s, double d) { return track_->position(track_->at(track_->wrap_s(s), d)); };
  tr.xy = at(tr.state[0], tr.state[1]);
  tr.velocity = (at(tr.state[0] + tr.state[2] * kStep, tr.state[1] + tr.state[3] * kStep) - tr.xy) / kStep;
  const track::Frenet f = track_->at(tr.state[0], tr.state[1]);
  const Eigen::Vector2d t = track_->segments()[f.seg].t, n = track_->segments()[f.seg].n;
  Eigen::Matrix2d J;  // (s, d) to (x, y) about here
  J.col(0) = t, J.col(1) = n;
  tr.xy_cov = J * tr.cov.topLeftCorner<2, 2>() * J.transpose();
}

}  // namespace brickyard::perception
