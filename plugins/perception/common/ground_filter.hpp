#pragma once
// The paper's vertical-feature ground filter (§III-B), framework-free.
//  1. Voxel filter: one point per occupied voxel (the centroid of its points), in the order the
//     voxels are first met.
//  2. z-vote: the voxels are projected to a 2-D grid and each votes for its cell through a hash
//     table of occupied cells only. A cell with fewer than `min_votes` voxels, or whose voxels
//     span less than `min_height` in z, is ground: the road, banked or not, gives a cell one or
//     two voxels; a wall, a pylon or a car stacks several. No plane is fitted, so no slope limit.
//  3. Two refinements at the edges of vertical features, each looking one cell around only (so a
//     banked road, 0.5 m x tan 20 deg = 0.18 m per cell, is never mistaken for a step):
//     - In a vertical cell, the voxels within `ground_band` of the road it stands on are road
//       (the asphalt at a wall's foot, under a pylon). That road height is the cell's lowest
//       voxel, confirmed by a ground neighbour within ground_band (the lowest such; the lower of
//       the two counts, so a cell holding only a wall's or a pylon's bottom measures from the
//       road beside it). Unconfirmed (a distant wall's stripe, hit a few rows up with no road in
//       its cell): vertical through.
//     - In a ground cell, voxels standing `min_height` above a vertical neighbour's lowest voxel
//       are not ground: on a banked turn the car is rolled, so in its frame a wall leans by the
//       bank angle and its top spills into the next cell (0.4 m for 1.2 m of wall at 20 deg).
#include "cell_map.hpp"
#include "points.hpp"

#include <array>

namespace brickyard::perception {

struct GroundParams {
  float leaf = 0.2f;        // m, voxel size
  float cell = 0.5f;        // m, 2-D vote grid
  int min_votes = 2;         // voxels in a cell for it to be a vertical feature
  float min_height = 0.2f;   // m, z extent of those voxels
  float ground_band = 0.15f; // m: in a vertical cell, voxels this close to the road it stands on are road
};

struct GroundResult {
  Points voxels;                  // voxel centroids
  std::vector<std::uint8_t> ground;  // per voxel: 1 ground, 0 vertical feature
  Points obstacles() const;       // the non-ground voxels
};

class GroundFilter {
 public:
  explicit GroundFilter(GroundParams p = {}) : p_(p) {}
  const GroundParams& params() const { return p_; }
  // Classifies a cloud (vehicle frame); points not finite or beyond kMaxCoordinate are skipped.
  // Reuses its tables between calls.
  void run(const Points& in, GroundResult& out);

 private:
  struct Voxel {
    float x, y, z;  // sums
    std::uint32_t n;
  };
  struct Cell {
    std::int32_t x, y;
    std::uint32_t votes;
    float zmin, zmax;
    float limit;  // its voxels below this are ground
  };
  // Steps 2 and 3 over either table of cells (32- or 64-bit keys), `key(x, y)` the cell's key.
  template <class Table, class Key> void vote(Table& cells, Key key, GroundResult& out);
  GroundParams p_;
  // voxel key -> index into voxels_: 32-bit keys when the frame's voxels fit, else 64-bit
  CellMap<std::uint32_t, std::uint32_t> voxel_index32_;
  CellMap<std::uint32_t> voxel_index_;
  std::vector<std::uint32_t> keys32_;
  std::vector<std::uint64_t> keys64_;
  std::vector<Voxel> voxels_;  // sums, the first voxel_count_ of them this frame's
  std::size_t voxel_count_ = 0;
  CellMap<std::uint32_t, std::uint32_t> cells32_;  // cell key -> index into cell_, likewise
  CellMap<std::uint32_t> cells_;
  std::vector<Cell> cell_;
  std::vector<std::array<std::int32_t, 2>> cell_xy_;  // per voxel
  std::vector<std::uint32_t> voxel_cell_;
};

// The voxel filter alone: centroids of the occupied voxels, in first-met order.
Points voxel_filter(const Points& in, float leaf);

}  // namespace brickyard::perception
