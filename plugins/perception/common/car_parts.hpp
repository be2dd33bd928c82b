#pragma once
// Cars as the obstacle detector gives them, made whole for the tracker (issue 46). Far off, a
// LiDAR meets a car's side at a grazing angle: each column a thin vertical stack of points, metres
// apart, each its own cluster; and it sees the faces turned to it only: the back of a car ahead,
// the front of one behind, an L of back and side at a slant. Each detection is first turned by a
// prior heading (`theta`: the track's direction where it is, and the course across it of a track
// followed there; less ours); the parts that fit within a car's footprint so turned (loosely)
// then say the car's own heading (the turn that boxes their outlines tightest), and turned by it
// the parts that fit one footprint are one car, completed to its footprint's centre: what is seen
// spans the car, its middle; else the car lies beyond the end (side) turned to us. Framework-free.
#include "perception/common/object_tracker.hpp"

#include <vector>

namespace brickyard::perception {

// A detection's prior heading (vehicle frame), and whether it is sure: the course of a car
// followed for a while, smoother than any one frame's sides (a car's sides seen at 70 m come
// degrees off from frame to frame); not sure, the car's seen sides may correct it.
struct PriorHeading {
  double theta = 0;
  bool sure = false;
};

// `in` (vehicle frame), each turned by its prior: the cars among them made whole, and what is not
// (a pylon) as it was. Sizes of a car: along and across its heading.
std::vector<Detection> whole_cars(const std::vector<Detection>& in, const std::vector<PriorHeading>& prior, const CarShape& car);

}  // namespace brickyard::perception
