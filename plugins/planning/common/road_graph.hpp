#pragma once
// The road graph (paper §III-C, after Stahl et al. 2019): a state lattice in the Frenet frame of
// the racing line, built offline, searched online around obstacles. Framework-free.
//
// Layers stand across the track every layer_spacing metres of the line (layer_spacing_turn where
// the line bends more than turn_curvature). A layer's nodes sit at d = k * lateral_step (the
// racing line itself is a node) between the track edges less half the car's width and a margin.
// An edge joins a node to a node of a layer 1, 2, 3, 4, 6 or 8 layers on (at most max_edge_length
// ahead; a sideways move needs length, and a long edge is a smooth lane change, where a chain of
// short ones would be a staircase). Along an edge d follows the quintic smoothstep
// d_a + (d_b - d_a)(10σ³ - 15σ⁴ + 6σ⁵): heading and curvature match the line's at every node, so
// any chain of edges is a smooth path. Each edge carries its length, ∫κ² dl, ∫|d| ds and the
// largest |κ| (edges above max_curvature are dropped; following the line itself is always kept).
#include "ref_line.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::planning {

struct RoadGraphParams {
  double layer_spacing = 10;          // m on straights
  double layer_spacing_turn = 5;      // m where the line's |κ| exceeds turn_curvature
  double turn_curvature = 1.0 / 500;  // 1/m
  double lateral_step = 0.5;          // m between nodes across the track
  double half_width = 0.97;           // m, half the car's width: the AV-21's for tests; the plugin and brickyard-plan take the vehicle file's
  double edge_margin = 1.5;           // m kept from the track edges beyond half the width: the path
                                      // tracker strays up to ~1 m at 50 m/s (docs/planning.md)
  double max_curvature = 0.05;        // 1/m: sharper edges are dropped
  double max_edge_length = 80;        // m
  bool operator==(const RoadGraphParams&) const = default;
};

// The track's edges across the line at s: (d of the right edge, d of the left edge), d measured
// from the line along its normal, left positive.
using TrackRoom = std::function<std::pair<double, double>(double s)>;

class RoadGraph {
 public:
  struct Layer {
    double s = 0;           // m along the line
    std::int32_t k0 = 0;    // nodes at d = (k0 + i) * lateral_step, i < count
    std::uint32_t count = 0;
    std::uint32_t first_node = 0;
    std::uint32_t reserved = 0;  // written as zero: no padding bytes of chance in the file
  };
  struct Edge {
    std::uint32_t to = 0;      // node
    float length = 0;          // m, along the edge
    float curvature = 0;       // ∫ κ² dl, 1/m
    float deviation = 0;       // ∫ |d| ds, m²
    float max_kappa = 0;       // 1/m
  };

  RoadGraph() = default;
  // Throws std::invalid_argument naming the s where the track is too narrow for a node.
  static RoadGraph build(const RefLine& line, const TrackRoom& room, const RoadGraphParams& p,
                         std::uint64_t source_digest = 0);
  // Binary file (format in docs/planning.md). load throws std::runtime_error naming the file and
  // what is wrong with it.
  void save(const std::string& path) const;
  static RoadGraph load(const std::string& path);

  const RoadGraphParams& params() const { return p_; }
  std::uint64_t source_digest() const { return digest_; }
  double length() const { return length_; }  // of the line, m
  const std::vector<Layer>& layers() const { return layers_; }
  std::size_t node_count() const { return node_layer_.size(); }
  std::size_t edge_count() const { return edges_.size(); }
  int layer_of(std::uint32_t node) const { return static_cast<int>(node_layer_[node]); }
  double node_s(std::uint32_t node) const { return layers_[node_layer_[node]].s; }
  double node_d(std::uint32_t node) const {
    const Layer& l = layers_[node_layer_[node]];
    return (l.k0 + static_cast<std::int32_t>(node - l.first_node)) * p_.lateral_step;
  }
  // Edges of a node: [first, last).
  const Edge* edges_begin(std::uint32_t node) const { return edges_.data() + first_edge_[node]; }
  const Edge* edges_end(std::uint32_t node) const { return edges_.data() + first_edge_[node + 1]; }
  // The first layer at or after s (cyclic), and the node of a layer nearest d.
  int layer_at_or_after(double s) const;
  std::uint32_t nearest_node(int layer, double d) const;

 private:
  RoadGraphParams p_;
  std::uint64_t digest_ = 0;
  double length_ = 0;
  std::vector<Layer> layers_;
  std::vector<std::uint32_t> node_layer_;
  std::vector<std::uint32_t> first_edge_;  // per node, and one past the last
  std::vector<Edge> edges_;
};

// Throws std::invalid_argument naming the first parameter outside its range (layer_spacing and
// layer_spacing_turn 1-100 m, lateral_step 0.1-5 m, half_width 0.1-5 m, edge_margin 0-20 m,
// max_curvature 0.001-1 1/m, max_edge_length 5-500 m, turn_curvature 0-1 1/m).
void check_params(const RoadGraphParams& p);

// d along an edge from (s_a, d_a) to (s_b, d_b) at s, and its derivatives in s.
struct EdgeShape {
  double s_a, d_a, s_b, d_b;
  double d(double s) const;
  double d1(double s) const;
  double d2(double s) const;
};

// Points of the curve d = e.d(s) beside the line every `step` m of s in [e.s_a, e.s_b) (s on the
// line, not wrapped), with the curve's curvature.
struct PathSample {
  double x, y, s, d, kappa;
};
void sample_shape(const RefLine& line, const EdgeShape& e, double step, std::vector<PathSample>& out);

// Curvature of the curve at offset d(s) from a line of curvature kappa_ref (its change along s
// neglected): (q d'' + κ_r (q² + 2 d'²)) / (q² + d'²)^(3/2), q = 1 - κ_r d.
double offset_curvature(double kappa_ref, double d, double d1, double d2);

}  // namespace brickyard::planning
