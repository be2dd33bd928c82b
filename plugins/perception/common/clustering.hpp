#pragma once
// Euclidean clustering, framework-free: the connected components of "closer than the tolerance",
// found with a hash grid of tolerance-sized cells (each cell's points are compared with its own
// and those of its 13 forward neighbours, so each pair of cells is visited once) and a
// union-find, then filtered by size. Same partition as PCL's
// EuclideanClusterExtraction on the same points (tested): clusters ordered by their first point,
// points in each ascending; a component larger than max_size is dropped, not split.
#include "cell_map.hpp"
#include "points.hpp"

#include <array>
#include <vector>

namespace brickyard::perception {

struct ClusterParams {
  float tolerance = 0.5f;  // m
  int min_size = 2;
  int max_size = 100000;
};

class EuclideanClustering {
 public:
  explicit EuclideanClustering(ClusterParams p = {}) : p_(p) {}
  const ClusterParams& params() const { return p_; }
  // Clusters as lists of indices into `points`, which must be in range (points.hpp: in_range;
  // the plugins drop the rest where clouds come in). Reuses its tables between calls.
  void run(const Points& points, std::vector<std::vector<int>>& clusters);

 private:
  int find(int i);
  // Buckets the points by cell and joins, in parent_, the pairs within the tolerance; over either
  // table (32- or 64-bit keys), `key(x, y, z)` a cell's key.
  template <class Table, class Key> void join_neighbours(const Points& pts, Table& cells, Key key);
  ClusterParams p_;
  CellMap<std::uint32_t, std::uint32_t> cells32_;  // cell key -> cell number, first-met order
  CellMap<std::uint32_t> cells_;                   // the same, 64-bit keys
  std::vector<std::array<std::int32_t, 3>> cell_xyz_;
  std::vector<std::uint32_t> cell_of_point_, begin_, fill_;
  std::vector<char> whole_;
  std::vector<int> order_, parent_, root_slot_, component_size_;
};

}  // namespace brickyard::perception
