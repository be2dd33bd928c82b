#pragma once
// What a mapping drive learns of the ground, framework-free: a 2-D grid in the map frame holding,
// per cell, the mean reflectivity of the LiDAR's ground returns that fell in it, their mean
// height, and where in it something stands (a wall: the mean place of the returns above the
// road). The track's edges and banking are read from it (track_extraction.hpp).
//
// Ground and standing are told apart by height in the vehicle frame, whose x-y plane is the road
// the car stands on (it tilts with a banked road): within `ground_band` of it, the ground; from
// `standing_from` up to `standing_to`, something standing if it also rises `standing_height` above
// the ground returns of its cell (or of the cells round it): the road's plane under the car is
// not the plane of ground 20 m away where the bank changes, nor of the level grass beyond a
// banked turn's lower edge, and those returned as walls. Nor a few standing returns among a cell's
// many road returns: one frame whose attitude is a degree or two off reads the road 20 m ahead as
// rising 1.4 m (IMS's mapped inner edge was 2.2 m inside the road where turn 2's bank runs out,
// one such return among 114 making a cell of the road a wall). Not the ground filter's vertical
// features: its 0.5 m cells count the asphalt at a wall's foot as the wall's, which put the
// mapped edges 0.2 to 0.4 m inside the walls.
//
// Reflectivity, not raw intensity: a return's intensity is the surface's reflectivity times the
// cosine of its incidence, and on the ground the cosine falls with range (a ray 10 m out from a
// sensor 1.2 m up meets the road at 7°). The cosine is taken against the vehicle's z axis, the
// normal of the road the car stands on (it tilts with a banked road), so the estimate is exact on
// the road under the car and only approximate on ground tilted from it: grass beyond a banked
// turn's lower edge lies level. Asphalt returns about a third of what grass does (0.15 against
// 0.45 in the simulator), so a threshold between them holds through that.
#include <Eigen/Geometry>

#include <cstdint>
#include <memory>
#include <unordered_map>

namespace brickyard::mapping {

struct RoadSurfaceParams {
  double cell = 0.2;          // m
  double max_range = 25;      // m from the sensor: farther, the ground's returns are too grazing
  double min_drop = 0.3;      // m a return must lie below the sensor to be the ground
  double min_cos = 0.03;      // a ray meeting the ground flatter than this (1.7°) says little
  double ground_band = 0.5;   // m above or below the car's road plane: the ground
  double standing_from = 0.5, standing_to = 3.0;  // m above it: maybe something standing,
  double standing_height = 0.6;  // when it also rises this far above the ground of its cell (or round it)
  double standing_share = 0.25;  // and its standing returns are at least this share of its ground returns
};

class RoadSurface {
 public:
  explicit RoadSurface(RoadSurfaceParams p = {}) : p_(p) {}
  const RoadSurfaceParams& params() const { return p_; }

  // One LiDAR's returns (sensor frame) with their intensities; vehicle_from_sensor is its mount,
  // map_from_vehicle the car's pose at the scan.
  void add_scan(const float* x, const float* y, const float* z, const float* intensity, std::size_t n,
                const Eigen::Isometry3d& vehicle_from_sensor, const Eigen::Isometry3d& map_from_vehicle);

  struct Sample {
    bool known = false;     // returns fell near enough
    double reflectivity = 0;
    double z = 0;           // the ground's height (has_z: some ground returns among the cells)
    bool has_z = false;
    bool standing = false;  // something stands in one of the cells: at standing_at (the mean place of its returns)
    Eigen::Vector2d standing_at = Eigen::Vector2d::Zero();
  };
  // The grid bilinearly interpolated at (x, y) over the four cells round it that hold returns
  // (a cell where something stands counts as reflectivity `standing_value`).
  Sample at(double x, double y, double standing_value) const;
  std::size_t cells() const { return cells_; }

 private:
  struct Cell {
    float refl_sum = 0, z_sum = 0;
    float sx = 0, sy = 0;  // standing returns' places, summed from the cell's corner (float keeps cm there)
    float s_zmax = -1e30f;  // the highest standing return (map frame)
    std::uint32_t n = 0, standing = 0;
  };
  static constexpr int kTile = 64;  // cells a side: storage only where the car has been
  struct Tile {
    Cell c[kTile * kTile];
  };
  Cell* cell(std::int64_t ix, std::int64_t iy, bool create);
  const Cell* cell(std::int64_t ix, std::int64_t iy) const;

  RoadSurfaceParams p_;
  std::unordered_map<std::uint64_t, std::unique_ptr<Tile>> tiles_;
  std::size_t cells_ = 0;
};

}  // namespace brickyard::mapping
