#pragma once
// The track's lines and banking from a mapping drive, framework-free (the paper's §III-C extracts
// the inner and outer lines from its map; the road graph is built on them).
//
// 1. The reference: one lap of the poses the car drove (map frame, in order), from `lap_from`
//    metres into the drive round to where the path comes back there, resampled every
//    `station_step` and smoothed.
// 2. The edges: at each station, out along the normal to each side, the first place where the
//    ground stops being road — its reflectivity crosses `threshold` (asphalt is dark, grass
//    bright) or something stands there (a wall) — found between samples `probe_step` apart on
//    the grid interpolated bilinearly, and placed where the interpolated reflectivity crosses the
//    threshold. A station whose side finds no edge (no returns there) takes its neighbours'.
//    Three times: the second and third across the centre line the one before found.
// 3. The widths filtered along the track (a median over `median_window` stations: a pylon left
//    on the road, or a patch of missing returns, is one station's outlier), the centre line moved
//    to the middle between the edges, the widths half their sum.
// 4. The banking: per station, the car's roll where it drove past (the median of the poses
//    nearest the station: the car stands on the road, so its roll is the road's bank there), or,
//    with no rolls given, the slope of the ground's height across the road between its edges (a
//    least-squares line through the interpolated heights); an angle, positive raising the left
//    edge, filtered along the track like the widths. Why the roll first: heights from two
//    passes of a drive meet in the same cells, and a few centimetres of height between the
//    passes, across a road the passes shared unevenly, read as degrees of bank (IMS, mapped at
//    40 m/s: up to 30° off from the map's heights; the car's registered roll: docs/mapping.md).
// 5. Written every `output_step` (6 m): a line planner takes the edges' station-to-station
//    jitter at 2 m for curvature. The written widths are narrowed where the straight segment
//    between two written points would claim road beyond a station's edge (the inside of a bend).
#include "road_surface.hpp"

#include "track/centre_line.hpp"

#include <string>
#include <vector>

namespace brickyard::mapping {

struct TrackExtractionParams {
  double station_step = 2.0;      // m between stations along the reference
  double output_step = 6.0;       // m between the track file's points (every few stations)
  double smooth = 10.0;           // m either side: the driven path's moving average
  double threshold = 0.30;        // reflectivity halfway between asphalt's and grass's (0.15, 0.45): unbiased where a cell straddles the edge
  double standing_value = 1.0;    // the reflectivity a cell where something stands counts as
  double probe_step = 0.05;       // m between samples out along a normal
  double strip = 1.0;             // m: each sample the mean over ±this along the track
  int strip_samples = 6;
  double max_half_width = 25;     // m from the reference a side's edge is looked for
  int median_window = 7;          // stations
  int bank_window = 15;           // stations: the bank's median (30 m; a bank ramps over 100 m)
  std::size_t pass_gap = 100;     // driven poses: a station seen again after more than these is a later pass
  int passes = 3;                 // the later ones across the last one's centre line
  double bank_margin = 1.0;       // m inside each edge left out of the bank's fit (kerbs, walls)
  double min_lap = 200;           // m: a drive shorter than this has not closed a lap
  double lap_from = 300;          // m into the drive the lap starts (the car's start is off its line)
  double close_within = 10;       // m: the path has come round when it passes this near its start
};

struct ExtractedTrack {
  track::CenterLine line;        // centre, widths and bank_deg (the track file's five columns)
  std::size_t stations = 0;
  std::size_t sides_found = 0;   // of 2 × stations: the rest took their neighbours' widths
  std::vector<Eigen::Vector2d> reference, normal;  // per station: the smoothed drive and its left normal
};

// Throws std::invalid_argument saying why (the path never closes a lap, no edge found anywhere).
// roll (when not null): the car's roll at each driven pose, rad (NaN: unknown there).
ExtractedTrack extract_track(const RoadSurface& surface, const std::vector<Eigen::Vector2d>& driven,
                             const TrackExtractionParams& p = {}, const std::vector<double>* roll = nullptr);

}  // namespace brickyard::mapping
