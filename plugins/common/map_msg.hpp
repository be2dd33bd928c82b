#pragma once
// The TrackMap message to and from the shared track geometry (libs/track). Plugin-side (SDK):
// the map source writes it, the car stack's adapters read it.
#include <brickyard/msgs/TrackMap.h>

#include "track/track.hpp"

namespace brickyard::plugins {

// The geometry's fields of any message that carries them under these names (TrackMap; the
// simulator's TrackWorld adds walls and pylons to the same fields).
template <class M> void write_geometry(M& m, const track::TrackGeometry& g) {
  m.name(g.name);
  m.source(g.line.source);
  m.x(g.line.x);
  m.y(g.line.y);
  m.width_right(g.line.width_right);
  m.width_left(g.line.width_left);
  m.bank(g.bank);
}

template <class M> void read_geometry(const M& m, track::TrackGeometry& g) {
  g.name = m.name();
  g.line.source = m.source();
  g.line.x = m.x();
  g.line.y = m.y();
  g.line.width_right = m.width_right();
  g.line.width_left = m.width_left();
  g.bank = m.bank();
}

inline msgs::TrackMap to_message(const track::TrackGeometry& g) {
  msgs::TrackMap m;
  write_geometry(m, g);
  return m;
}

inline track::TrackGeometry from_message(const msgs::TrackMap& m) {
  track::TrackGeometry g;
  read_geometry(m, g);
  return g;
}

}  // namespace brickyard::plugins
