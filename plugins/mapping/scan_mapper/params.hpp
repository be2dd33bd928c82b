#pragma once
// mapping.scan_mapper's parameters (plugin.cpp): the mapper's, the road surface's and the track
// extraction's, the estimate's age, gravity's level, and the files written at the end.
// Plugin-side (SDK).
#include <brickyard/plugin.hpp>

#include "mapping/common/mapping_run.hpp"

#include <string>

namespace brickyard::mapping {

// What the graph says: the run's own settings (bound as members of this struct), and the files
// the plugin writes at the end.
struct Settings : MappingRunParams {
  std::string map_file;    // empty: none
  std::string track_file;  // empty: none
};

inline ParamBinding<Settings> bindings() {
  using M = ScanMapperParams;
  ParamBinding<Settings> b;
  b.bind("coarse_voxel", &Settings::mapper, &M::coarse_voxel).in_unit("m").range(0.05, 10)
      .doc("the map registered on first, from the estimate: reaches far");
  b.bind("fine_voxel", &Settings::mapper, &M::fine_voxel).in_unit("m").range(0.02, 10)
      .doc("then on this one, accurate near the answer; also the map written out");
  b.bind("keyframe_distance", &Settings::mapper, &M::keyframe_distance).in_unit("m").range(0, 1000)
      .doc("a frame joins the map once the car has moved this far since the last one");
  b.bind("max_range", &Settings::mapper, &M::max_range).in_unit("m").range(1, 1000).doc("points farther from the car are left out");
  b.bind("max_correction", &Settings::mapper, &M::max_correction).in_unit("m").range(0, 100)
      .doc("a registration moving the estimate farther is not taken");
  b.bind("max_turn", &Settings::mapper, &M::max_turn).in_unit("rad").range(0, 3.14).doc("nor one turning it more");
  b.bind("face_neighbours", &Settings::mapper, &M::registration, &RegistrationParams::face_neighbours)
      .doc("each point matched to its voxel and the 6 sharing a face (VGICP's DIRECT7); off: its own (DIRECT1)");
  b.bind("map_file", &Settings::map_file).doc("the map written here at the end (PCD, binary x y z); empty: not written");
  b.bind("track_file", &Settings::track_file)
      .doc("the track's centre line, widths and banking extracted from the drive (one lap at least; the scan inputs wired), "
           "written here at the end as a track file; empty: not written");
  b.bind("road_cell", &Settings::surface, &RoadSurfaceParams::cell).in_unit("m").range(0.02, 2)
      .doc("the road surface's grid: each cell's mean reflectivity and height");
  b.bind("road_range", &Settings::surface, &RoadSurfaceParams::max_range).in_unit("m").range(1, 200)
      .doc("returns farther from their LiDAR are left out of the road surface (too grazing)");
  b.bind("edge_reflectivity", &Settings::extraction, &TrackExtractionParams::threshold).range(0, 10)
      .doc("the road's edge: where the ground's reflectivity rises past this (asphalt below, grass above)");
  b.bind("station_step", &Settings::extraction, &TrackExtractionParams::station_step).in_unit("m").range(0.1, 50)
      .doc("the extracted track's points: this far apart along the drive");
  b.bind("max_estimate_age", &Settings::max_estimate_age).in_unit("s").range(0, 60)
      .doc("a frame with no estimate within this of its stamp is left out");
  b.bind("level_on_ground", &Settings::level_on_ground)
      .doc("frames join the map with their ground's roll, pitch and height (the walls tilt the whole frame's registration) and, "
           "while the estimate is NORMAL, on its (x, y); off: on the pose found");
  b.bind("level_window", &Settings::level_window).in_unit("s").range(0.5, 60)
      .doc("gravity's level (imu wired): the attitude's drift is its mean less gravity's over this window");
  b.bind("level_time", &Settings::level_time).in_unit("s").range(0.1, 600)
      .doc("and is turned out of the frames joining the map over about this time (a part each frame)");
  b.not_above("fine_voxel", "coarse_voxel");
  return b;
}

}  // namespace brickyard::mapping
