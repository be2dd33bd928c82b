#pragma once
// Ouster ranges to points in the sensor frame, as the sensor documentation's "Lidar Range to XYZ"
// gives them: for beam (row) i in the column with measurement id c of a W-column frame,
//   theta_e = 2 pi (1 - c / W)                      the encoder angle (encoder count c * 90112 / W)
//   theta_a = -2 pi beam_azimuth_angles[i] / 360,   phi = 2 pi beam_altitude_angles[i] / 360
//   x = (r - n) cos(theta_e + theta_a) cos(phi) + n cos(theta_e)
//   y = (r - n) sin(theta_e + theta_a) cos(phi) + n sin(theta_e)
//   z = (r - n) sin(phi)
// with r the range and n lidar_origin_to_beam_origin_mm, then lidar_to_sensor_transform applied.
// Where beam_to_lidar_transform moves the beam origin along z too, n is the origin's distance and
// its z is added to z (the documented formula is the case z = 0, which every shipped file has).
// The table holds, per pixel, the unit direction and the offset so that p = r * direction + offset;
// the staggering of the image (pixel_shift_by_row) plays no part: each pixel's own column fixes
// its angle. Sources: docs/drivers-formats.md, "Ouster LiDAR packets".
#include "ouster_frame.hpp"
#include "ouster_metadata.hpp"

#include <cstdint>
#include <vector>

namespace brickyard::drivers {

class OusterXyzTable {
 public:
  explicit OusterXyzTable(const OusterMetadata& metadata);

  int width() const { return width_; }
  int height() const { return height_; }
  // Per pixel (row * width + column), sensor frame, millimetres: x, y, z in turn.
  const std::vector<float>& direction() const { return direction_; }
  const std::vector<float>& offset_mm() const { return offset_mm_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<float> direction_;
  std::vector<float> offset_mm_;
};

// The points of a frame's returns, in metres in the sensor frame, one per pixel with a range in
// a column that arrived (range 0: no return). Time: the column's timestamp; intensity: the
// reflectivity.
struct OusterCloud {
  std::vector<float> x, y, z, intensity;
  std::vector<uint64_t> time_ns;
  std::vector<uint32_t> pixel;  // row * width + column, for tracing a point to its pixel
  void clear();
};

// Fills `cloud` (cleared first) from the frame's first return, or its second (dual profile).
void ouster_frame_to_cloud(const OusterFrame& frame, const OusterXyzTable& table, OusterCloud& cloud,
                           bool second_return = false);

}  // namespace brickyard::drivers
