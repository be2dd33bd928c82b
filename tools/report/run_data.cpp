#include "run_data.hpp"

#include <brickyard/msgs/ControlCommandPubSubTypes.h>
#include <brickyard/msgs/GnssFixPubSubTypes.h>
#include <brickyard/msgs/LocalizationEstimatePubSubTypes.h>
#include <brickyard/msgs/ModeStatusPubSubTypes.h>
#include <brickyard/msgs/PathPubSubTypes.h>
#include <brickyard/msgs/TrackWorldPubSubTypes.h>
#include <brickyard/msgs/VehicleStatePubSubTypes.h>

#include <fastdds/rtps/common/SerializedPayload.h>

#include "replay/common/recording.hpp"

#include <brickyard/message_traits.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace brickyard::report {
namespace {

using replay::RecordedTopic;
using replay::Recording;

template <class T, class PubSub>
std::vector<T> decode(const Recording& rec, const RecordedTopic& topic, std::vector<std::string>& notes) {
  PubSub type;
  std::vector<T> out;
  if (topic.type_hash != message_traits<T>::hash) {  // recorded with another definition of the type
    notes.push_back(topic.name + " was recorded with another definition of " + topic.type + ": not drawn");
    return out;
  }
  for (const auto& s : rec.samples(topic)) {
    eprosima::fastrtps::rtps::SerializedPayload_t payload(static_cast<std::uint32_t>(s.data.size()));
    std::memcpy(payload.data, s.data.data(), s.data.size());
    payload.length = static_cast<std::uint32_t>(s.data.size());
    T m;
    if (!type.deserialize(&payload, &m)) throw std::runtime_error(rec.path() + ": a sample of " + topic.name + " does not decode");
    out.push_back(std::move(m));
  }
  return out;
}

std::vector<const RecordedTopic*> of_type(const Recording& rec, const std::string& type) {
  std::vector<const RecordedTopic*> out;
  for (const auto& t : rec.topics())
    if (t.type == "brickyard::msgs::" + type) out.push_back(&t);
  return out;
}

std::string node_of(const std::string& topic) { return topic.substr(0, topic.find('.')); }

double secs(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

}  // namespace

RunData read_run(const std::string& path) {
  Recording rec(path);
  RunData d;
  if (auto w = of_type(rec, "TrackWorld"); !w.empty()) {
    const auto worlds = decode<msgs::TrackWorld, msgs::TrackWorldPubSubType>(rec, *w.front(), d.notes);
    if (!worlds.empty()) {
      const auto& m = worlds.front();
      const std::size_t n = m.x().size();
      const bool whole = n > 2 && m.y().size() == n && m.width_left().size() == n && m.width_right().size() == n;
      if (!whole) d.notes.push_back("the TrackWorld's sequences disagree in length: no track edges");
      for (std::size_t i = 0; whole && i <= n; ++i) {
        const std::size_t k = i % n, a = (k + n - 1) % n, b = (k + 1) % n;
        double tx = m.x()[b] - m.x()[a], ty = m.y()[b] - m.y()[a];
        const double len = std::hypot(tx, ty);
        if (!(len > 0)) continue;
        tx /= len;
        ty /= len;
        d.left_x.push_back(m.x()[k] - ty * m.width_left()[k]);
        d.left_y.push_back(m.y()[k] + tx * m.width_left()[k]);
        d.right_x.push_back(m.x()[k] + ty * m.width_right()[k]);
        d.right_y.push_back(m.y()[k] - tx * m.width_right()[k]);
      }
      for (const auto& p : m.pylons()) d.pylons.push_back({p.x(), p.y(), p.radius(), p.s(), p.d()});
      if (whole) {
        d.centre_x = m.x();
        d.centre_y = m.y();
        d.width_left = m.width_left();
        d.width_right = m.width_right();
      }
    }
  } else {
    d.notes.push_back("no TrackWorld topic: no track edges");
  }
  if (auto v = of_type(rec, "VehicleState"); !v.empty()) {
    for (const auto& m : decode<msgs::VehicleState, msgs::VehicleStatePubSubType>(rec, *v.front(), d.notes))
      d.truth.push_back({secs(m.header().stamp_ns()), m.x(), m.y(), std::hypot(m.vx(), m.vy()), m.s(), m.d()});
  } else {
    d.notes.push_back("no VehicleState topic: no driven path, error or speed");
  }
  for (const auto* t : of_type(rec, "GnssFix"))
    for (const auto& m : decode<msgs::GnssFix, msgs::GnssFixPubSubType>(rec, *t, d.notes))
      if (m.valid()) d.fixes.push_back({secs(m.header().stamp_ns()), m.x(), m.y(), m.receiver_id()});
  std::string estimator;
  if (auto e = of_type(rec, "LocalizationEstimate"); !e.empty()) {
    estimator = node_of(e.front()->name);
    for (const auto& m : decode<msgs::LocalizationEstimate, msgs::LocalizationEstimatePubSubType>(rec, *e.front(), d.notes))
      d.estimates.push_back({secs(m.header().stamp_ns()), m.x(), m.y(), m.delta()});
  } else {
    d.notes.push_back("no LocalizationEstimate topic: no error or Δk figures");
  }
  // Status timelines: the estimator's ModeStatus is the localization manager's; another node's
  // (the system manager's) is the driving mode.
  for (const auto* t : of_type(rec, "ModeStatus")) {
    auto& into = node_of(t->name) == estimator ? d.localization : d.manager;
    if (!into.empty()) continue;
    for (const auto& m : decode<msgs::ModeStatus, msgs::ModeStatusPubSubType>(rec, *t, d.notes))
      into.push_back({secs(m.header().stamp_ns()), m.mode(), m.mode_name()});
  }
  for (const auto* t : of_type(rec, "ControlCommand")) {
    std::vector<Steer> s;
    for (const auto& m : decode<msgs::ControlCommand, msgs::ControlCommandPubSubType>(rec, *t, d.notes))
      s.push_back({secs(m.header().stamp_ns()), m.steer()});
    d.commands.emplace_back(t->name, std::move(s));
  }
  if (auto p = of_type(rec, "Path"); !p.empty()) {
    for (const auto& m : decode<msgs::Path, msgs::PathPubSubType>(rec, *p.front(), d.notes)) {
      PathSnapshot s{secs(m.header().stamp_ns()), {}, {}};
      for (const auto& q : m.poses()) {
        s.x.push_back(q.x());
        s.y.push_back(q.y());
      }
      d.paths.push_back(std::move(s));
    }
  }
  return d;
}

std::pair<double, double> to_track(const RunData& d, double x, double y) {
  const std::size_t n = d.centre_x.size();
  double best = 1e300, bs = 0, bd = 0, s0 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const double ex = d.centre_x[j] - d.centre_x[i], ey = d.centre_y[j] - d.centre_y[i], len = std::hypot(ex, ey);
    if (len > 0) {
      const double u = std::clamp(((x - d.centre_x[i]) * ex + (y - d.centre_y[i]) * ey) / (len * len), 0.0, 1.0);
      const double px = d.centre_x[i] + u * ex - x, py = d.centre_y[i] + u * ey - y, dist = px * px + py * py;
      if (dist < best) {
        best = dist;
        bs = s0 + u * len;
        bd = ((x - d.centre_x[i]) * -ey + (y - d.centre_y[i]) * ex) / len;
      }
    }
    s0 += len;
  }
  return {bs, bd};
}

}  // namespace brickyard::report
