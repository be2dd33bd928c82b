#pragma once
// An Ouster sensor's metadata JSON (what the sensor's HTTP API or the SDK saves beside a capture)
// read into a plain struct, framework-free: the lidar packet layout (profile, columns per packet and
// frame, pixels per column, column window), the beam intrinsics and the lidar-to-sensor transform
// that turn ranges into points, and the sensor's identity (serial, init id, firmware) that packets
// are checked against. Two layouts are read: the flat one of firmware 2.x / ouster_client 0.3
// (beam angles at the top, "data_format"), and the nested one of later SDKs ("beam_intrinsics",
// "lidar_data_format", "lidar_intrinsics", "sensor_info", "config_params"). A malformed file is
// refused with an error that names the field. Fields and where they are documented:
// docs/drivers-formats.md, "Ouster LiDAR packets".
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::drivers {

// udp_profile_lidar: how each pixel is laid out in a lidar packet.
enum class OusterProfile {
  legacy,         // LEGACY (or no profile named: firmware before 2.2)
  single_return,  // RNG19_RFL8_SIG16_NIR16
  low_data_rate,  // RNG15_RFL8_NIR8
  dual_return,    // RNG19_RFL8_SIG16_NIR16_DUAL
};

const char* to_string(OusterProfile profile);

struct OusterMetadata {
  OusterProfile profile = OusterProfile::legacy;
  int columns_per_packet = 16;
  int columns_per_frame = 1024;
  int pixels_per_column = 0;
  std::vector<int> pixel_shift_by_row;  // one per row: destaggers the image (not used for xyz)
  int column_window_first = 0;          // the columns the sensor fires in; the window may wrap past
  int column_window_last = 0;           // the frame's end, first > last
  std::string lidar_mode;               // "1024x10"
  int frames_per_second = 0;            // from lidar_mode: 10 or 20

  std::vector<double> beam_altitude_deg;  // one per row
  std::vector<double> beam_azimuth_deg;   // one per row
  double lidar_origin_to_beam_origin_mm = 0.0;
  // Row-major 4x4 homogeneous transforms, translations in millimetres. The beam-to-lidar one is
  // [1 0 0 n; 0 1 0 0; 0 0 1 0; 0 0 0 1] when the file has none (n: the origin offset above).
  std::array<double, 16> beam_to_lidar{};
  std::array<double, 16> lidar_to_sensor{};
  std::array<double, 16> imu_to_sensor{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

  uint64_t serial_number = 0;       // prod_sn; 0 when the file has none
  uint32_t initialization_id = 0;   // changes at every sensor start; 0 when the file has none
  int firmware_major = 0;           // from image_rev ("...-v2.3.0+...") or build_rev; 0 if unknown
  int firmware_minor = 0;
  std::string product_line;         // "OS-2-128"
  int udp_port_lidar = 7502;
  int udp_port_imu = 7503;
  // Whether lidar packets end with a CRC-64: firmware 3.1 and later (a caller may override).
  bool packet_crc = false;

  int columns_in_window() const {
    return (column_window_last - column_window_first + columns_per_frame) % columns_per_frame + 1;
  }
  bool column_in_window(int column) const {
    return (column - column_window_first + columns_per_frame) % columns_per_frame < columns_in_window();
  }
};

// Reads `json_text` into `out`. On failure returns false and `error` names the field, e.g.
// "lidar_data_format.pixel_shift_by_row: expected 128 integers (pixels_per_column), got 127".
bool parse_ouster_metadata(std::string_view json_text, OusterMetadata& out, std::string& error);

}  // namespace brickyard::drivers
