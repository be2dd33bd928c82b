#pragma once
// Ray casting LiDAR against the track world: the banked road surface, the walls and the pylons;
// and other cars, when a frame is given them (lidar_cars.hpp).
// Framework-free. Rays march segment by segment along the centre line from the sensor's segment,
// so a ray costs a few segment steps whatever the size of the track (see docs/simulator.md).
#include "lidar_cars.hpp"
#include "rng.hpp"
#include "track.hpp"

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace brickyard::sim {

// grass: the ground beyond the road's edges (level at the edge's height), which returns more of
// a LiDAR's near-infrared light than asphalt: what shows a mapping drive where an edge without a
// wall is (docs/mapping.md).
enum class Surface : unsigned char { none = 0, road = 1, wall = 2, pylon = 3, grass = 4, car = 5 };

struct RayHit {
  double range = 0;  // m along the ray
  Surface surface = Surface::none;
  double cos_incidence = 1;
};

struct LidarSpec {
  Eigen::Vector3d mount = Eigen::Vector3d::Zero();  // m, vehicle (base_link) frame
  double roll = 0, pitch = 0, yaw = 0;              // rad, mount orientation
  double h_fov = 120 * M_PI / 180;                  // rad, centred on the sensor's x axis
  int columns = 850;
  std::vector<double> elevations;                   // rad, one per row
  double min_range = 1.0, max_range = 200.0;        // m
  double range_noise = 0.02;                        // m, 1 sigma
  double dropout = 0.0;                             // probability a return is lost
  bool use_blocks = true;                           // off: walk every slab (benchmark baseline)
  bool coherent_columns = true;                     // off: every ray marches from the sensor
  bool skip_escaped_rows = true;                    // off: rows above an escaped row are cast (tests)
  bool simd = true;                                 // off: ray by ray, not 4 columns in AVX2 lanes (tests; same bits)
  // SIMD path: the columns marched on this many threads (1 or 2; same bits). One by default: on
  // the sim clock the executive already steps a car's LiDARs side by side, and a second thread
  // per frame there only costs its start (docs/performance.md).
  int threads = 1;
  double reflectivity_road = 0.15, reflectivity_wall = 0.6, reflectivity_pylon = 0.9, reflectivity_grass = 0.45;
  double reflectivity_car = 0.5;  // painted bodywork
};

// Row elevations: "uniform" spacing, or "horizon": rows concentrated near 0 deg as the Hydra
// does (elevation = limit * |u|^exponent, u evenly spaced in [-1, 1]).
std::vector<double> row_elevations(int rows, double lo_deg, double hi_deg, const std::string& spacing,
                                   double exponent);

// Points of one frame, sensor frame. With record_surface, also what each point hit (the ground
// truth perception is scored against; off in the plugin).
struct PointBuffers {
  std::vector<float> x, y, z, intensity;
  std::vector<Surface> surface;
  bool record_surface = false;
  void clear() { x.clear(); y.clear(); z.clear(); intensity.clear(); surface.clear(); }
};

class LidarCaster {
 public:
  LidarCaster(const Track& track, LidarSpec spec);
  const LidarSpec& spec() const { return spec_; }

  // Where a ray may start its march instead of at the sensor: the next row up in a column is
  // known to pass everything the row below it passed, up to a point (see scan and
  // docs/simulator.md). `margin`: how far the path before t stays from any wall.
  struct Resume {
    double t = 0;
    int seg = -1;
    double margin = 0;
    bool rest_escape = false;  // the rays above this one return nothing either
    // When the ray escaped with its whole path clear of pylon slabs: where (t), and how far the
    // path stayed from every wall line (> 0). scan's rows_above_escape takes it from there.
    double escape_t = 0, escape_margin = 0;
  };

  // First hit of the ray o + t v (world frame, v unit) within max_range; `seg` is the centre-line
  // segment o lies on (Track::project).
  RayHit cast(const Eigen::Vector3d& o, const Eigen::Vector3d& v, int seg) const {
    return cast(o, v, seg, nullptr, -1, -1, nullptr);
  }
  // The same, starting at `from` (when not null). When `checkpoint` is not null, also: the last
  // slab entry up to which a ray whose points lie within shift * t of this one's, and above them,
  // is sure to meet nothing (checkpoint->seg < 0: none past the start); and whether every ray
  // within shift_rest * t, and above, escapes as this one did (to max range or above all).
  RayHit cast(const Eigen::Vector3d& o, const Eigen::Vector3d& v, int seg, const Resume* from, double shift,
              double shift_rest, Resume* checkpoint) const;

  // One frame from a vehicle pose (world_from_body), the other cars where they are. Noise sigma
  // is multiplied by noise_factor. Returns the number of rays cast.
  std::size_t scan(const Eigen::Isometry3d& world_from_body, int seg_hint, Rng& rng, double noise_factor,
                   PointBuffers& out, const std::vector<CarBody>& cars = {}) const;

 private:
  // Whether every row above r of a column surely returns nothing, given that row r escaped (see
  // the definition for the argument).
  bool rows_above_escape(const Eigen::Vector3d* dw, int r, int rows, double oz, const Resume& escaped,
                         const std::vector<int>& near_pylons, const Eigen::Vector3d& o) const;
  RayHit march(const Eigen::Vector3d& o, const Eigen::Vector3d& v, int seg, const Resume* from, double shift,
               double shift_rest, Resume* checkpoint) const;
  // march's state and steps (lidar_march.hpp).
  struct RayMarch;
  // A hit's point (range noise, dropout, range limits, intensity) into staging buffers that are
  // appended to the frame a column, or a group of columns, at a time.
  struct Staging;
  // What both scans work out first for a frame: the sensor's origin and axes in the world, its
  // segment, the noise, the ray count (the output reserved for it), the pylons and cars within reach.
  struct Frame {
    Eigen::Vector3d o;
    Eigen::Matrix3d R;
    int seg = 0;
    double sigma = 0;
    std::size_t rays = 0;
    std::vector<int> near_pylons;
    FrameCars cars;
  };
  Frame begin_frame(const Eigen::Isometry3d& world_from_body, int seg_hint, double noise_factor, PointBuffers& out,
                    const std::vector<CarBody>& cars) const;
  // The world's hit on the ray of row r, column c, or a car's when one is nearer.
  RayHit with_cars(const Frame& f, const RayHit& world, int r, int c) const;
  void add_point(const RayHit& h, int r, int c, double sigma, Rng& rng, Staging& st) const;
  // scan for W neighbouring columns at a time, their rays of a row marched together in SIMD lanes
  // (march_lanes: each lane does march's operations in march's order, so the same bits).
  template <int W> struct Lanes;
  template <int W> void march_lanes(const Eigen::Vector3d& o, int seg, Lanes<W>& L) const;
  // march_lanes's state and steps (lidar_lanes.cpp).
  template <int W> struct LaneMarch;
  // What marching columns [c0, c1) of a frame leaves for its points: per ray, in groups of W
  // columns (row by row, the W lanes side by side), the range, surface and cosine; per column,
  // the rows cast. Pure: the columns of a frame may be marched on two threads.
  struct ColumnHits {
    int rows = 0;
    std::vector<double> range, cos;
    std::vector<long> surf;
    std::vector<int> cast;
  };
  // scratch of scan_lanes, kept between frames (no allocation per frame): one caster scans on one
  // thread at a time (it splits its own columns over two)
  mutable ColumnHits hits_;
  // The groups of W columns first, first + stride, ... (two threads take every other group: the
  // columns that meet a near wall and those that look far are spread over both).
  template <int W> void march_columns(const Frame& f, int first, int stride, ColumnHits& h) const;
  // march_columns's scratch and steps for a group of W columns (lidar_lanes.cpp).
  template <int W> struct GroupRays;
  void march_columns_avx2(const Frame& f, int first, int stride, ColumnHits& h) const;
  template <int W>
  std::size_t scan_lanes(const Frame& f, Rng& rng, PointBuffers& out) const;
  std::size_t scan_one_by_one(const Frame& f, Rng& rng, PointBuffers& out) const;
  std::size_t scan_avx2(const Frame& f, Rng& rng, PointBuffers& out) const;
  // The constructor's steps, in the order it takes them: the pylons sorted by segment (returns each
  // one's segment), the segments' and the blocks' tables, the heights within reach of each block,
  // the rays' directions and the bound on the road's gradient.
  std::vector<int> sort_pylons_by_segment();
  void build_segments(const std::vector<int>& pylon_seg);
  void build_blocks(const std::vector<int>& pylon_seg);
  void find_tops_within_reach();
  void build_ray_directions();
  void bound_road_slope();
  // Per segment, everything as a function of a (m along the segment from its start).
  struct Seg {
    double px, py, tx, ty, len;
    double wl0, dwl, wr0, dwr;     // road edges: d = +wl (left), -wr (right)
    double tb0, dtb;               // tan(bank)
    double inv_n0;                 // 1 / sqrt(1 + tb0²): the road normal's norm at a = 0
    double wall_l, wall_r;         // wall lines at a = 0: d (+inf / -inf when absent); same slope as the edges
    int pylon_begin, pylon_end;    // into pylons_
  };
  // Runs of kBlock segments a ray may cross in one step when it stays above everything in them
  // and inside their walls (long rays near the horizon would otherwise walk every slab).
  static constexpr int kBlock = 8;
  struct Block {
    double sx, sy, stx, sty;  // start point and the normal of the entry plane (first segment's tangent)
    double ex, ey, etx, ety;  // end point and the normal of the exit plane (last segment's tangent)
    double cx, cy, ctx, cty;  // chord frame: origin and unit direction
    double z_max;             // highest road, edge or pylon top in the block
    double dl_safe, dr_safe;  // chord-frame d between which no wall can be reached
    double z_top_near;        // highest point (walls included) of the blocks within max range
  };
  std::vector<Block> blocks_;
  const Track& track_;
  LidarSpec spec_;
  std::vector<Seg> seg_;
  std::vector<Pylon> pylons_;      // sorted by segment
  double wall_left_off_, wall_right_off_, wall_h_;
  bool wall_left_, wall_right_;
  Eigen::Isometry3d body_from_sensor_;
  std::vector<double> col_c_, col_s_, row_c_, row_s_;  // rows sorted by elevation, lowest first
  double slope_max_ = 0;                               // bound on the road surface's gradient
  double z_top_all_ = 0;                               // the highest point of the world
};

}  // namespace brickyard::sim
