#pragma once
// NovAtel OEM7 logs as plain structs, framework-free: the header every log carries and the four
// logs the car reads (BESTPOS, BESTVEL, INSPVAX, RAWIMUSX). Field meanings and units are the OEM7
// Commands and Logs reference's (docs/drivers-formats.md names each page); enums keep the
// receiver's numbers, so a value this code has no name for still arrives intact.
#include <cstdint>
#include <string>
#include <variant>

namespace brickyard::drivers {

// Message IDs (OEM7 reference, each log's page).
inline constexpr uint16_t kBestPosId = 42;
inline constexpr uint16_t kBestVelId = 99;
inline constexpr uint16_t kRawImuSXId = 1462;
inline constexpr uint16_t kInsPvaXId = 1465;

// "GPS Reference Time Status": how well the receiver knows the time in the header.
enum class TimeStatus : uint8_t {
  unknown = 20, approximate = 60, coarse_adjusting = 80, coarse = 100, coarse_steering = 120,
  freewheeling = 130, fine_adjusting = 140, fine = 160, fine_backup_steering = 170, fine_steering = 180,
  sattime = 200,
};

// "Solution Status" of BESTPOS and BESTVEL.
enum class SolutionStatus : uint32_t {
  computed = 0, insufficient_obs = 1, no_convergence = 2, singularity = 3, cov_trace = 4, test_dist = 5,
  cold_start = 6, v_h_limit = 7, variance = 8, residuals = 9, delta_pos = 10, negative_var = 11,
  integrity_warning = 13, pending = 18, invalid_fix = 19, unauthorized = 20,
};

// "Position or Velocity Type": where a solution came from (single point, RTK fixed, INS-aided ...).
enum class PositionType : uint32_t {
  none = 0, fixedpos = 1, fixedheight = 2, doppler_velocity = 8, single = 16, psrdiff = 17, waas = 18,
  propagated = 19, l1_float = 32, ionofree_float = 33, narrow_float = 34, l1_int = 48, wide_int = 49,
  narrow_int = 50, rtk_direct_ins = 51, ins_sbas = 52, ins_psrsp = 53, ins_psrdiff = 54, ins_rtkfloat = 55,
  ins_rtkfixed = 56, ppp_converging = 68, ppp = 69, operational = 70, warning = 71, out_of_bounds = 72,
  ins_ppp_converging = 73, ins_ppp = 74, ppp_basic_converging = 77, ppp_basic = 78,
  ins_ppp_basic_converging = 79, ins_ppp_basic = 80,
};

// "Inertial Solution Status" of INSPVAX.
enum class InsStatus : uint32_t {
  inactive = 0, aligning = 1, high_variance = 2, solution_good = 3, solution_free = 6,
  alignment_complete = 7, determining_orientation = 8, waiting_initial_pos = 9, waiting_azimuth = 10,
  initializing_biases = 11, motion_detect = 12,
};

// BESTPOS's datum: the binary log carries the DATUM table's number, the ASCII log its name; only
// the two a car uses are named here (any other ASCII name is refused as malformed).
inline constexpr uint32_t kDatumWgs84 = 61;
inline constexpr uint32_t kDatumUser = 63;

// Which of the four framings a log arrived in (or is to be written in).
enum class Oem7Framing : uint8_t { binary, binary_short, ascii, ascii_short };

// The log header. Short headers (RAWIMUSX) carry only the message ID, week and milliseconds; the
// other fields are then left at their defaults.
struct Oem7Header {
  Oem7Framing framing = Oem7Framing::binary;
  uint16_t message_id = 0;
  uint8_t port_address = 0;  // binary: the port's number in the OEM7 port table; ASCII: 0
  std::string port;          // ASCII: the port's name ("COM1", "USB1"); binary: empty
  uint16_t sequence = 0;     // counts down the related logs of one set; usually 0
  float idle_percent = 0;    // processor idle time, % (binary sends twice the percentage, 0-200)
  TimeStatus time_status = TimeStatus::unknown;
  uint16_t week = 0;          // GPS week (not modulo 1024)
  uint32_t milliseconds = 0;  // GPS time of week, ms
  uint32_t receiver_status = 0;
  uint16_t reserved = 0;
  uint16_t receiver_sw_version = 0;

  bool operator==(const Oem7Header&) const = default;
};

// BESTPOS: the receiver's best position, at the antenna phase centre (GNSS, or GNSS+INS on SPAN).
struct BestPos {
  Oem7Header header;
  SolutionStatus solution_status = SolutionStatus::insufficient_obs;
  PositionType position_type = PositionType::none;
  double latitude_deg = 0, longitude_deg = 0;
  double height_msl_m = 0;  // above mean sea level; ellipsoidal height = height_msl_m + undulation_m
  float undulation_m = 0;   // geoid above the datum's ellipsoid
  uint32_t datum_id = kDatumWgs84;
  float latitude_sigma_m = 0, longitude_sigma_m = 0, height_sigma_m = 0;  // 1-sigma standard deviations
  std::string base_station_id;  // up to 4 characters
  float differential_age_s = 0, solution_age_s = 0;
  uint8_t satellites_tracked = 0, satellites_in_solution = 0;
  uint8_t satellites_l1_in_solution = 0, satellites_multi_in_solution = 0;
  uint8_t reserved = 0;
  uint8_t extended_solution_status = 0;
  uint8_t galileo_beidou_signal_mask = 0, gps_glonass_signal_mask = 0;

  bool operator==(const BestPos&) const = default;
};

// BESTVEL: the best velocity, over ground. Its time of validity is the header's time minus latency.
struct BestVel {
  Oem7Header header;
  SolutionStatus solution_status = SolutionStatus::insufficient_obs;
  PositionType velocity_type = PositionType::none;
  float latency_s = 0;
  float differential_age_s = 0;
  double horizontal_speed_mps = 0;
  double track_over_ground_deg = 0;  // direction of travel from true north, degrees
  double vertical_speed_mps = 0;     // positive up
  float reserved = 0;

  bool operator==(const BestVel&) const = default;
};

// INSPVAX: the INS's position, velocity and attitude with their standard deviations (SPAN).
struct InsPvaX {
  Oem7Header header;
  InsStatus ins_status = InsStatus::inactive;
  PositionType position_type = PositionType::none;
  double latitude_deg = 0, longitude_deg = 0, height_msl_m = 0;
  float undulation_m = 0;
  double north_velocity_mps = 0, east_velocity_mps = 0, up_velocity_mps = 0;
  double roll_deg = 0, pitch_deg = 0, azimuth_deg = 0;  // local level; azimuth from the IMU and filter
  float latitude_sigma_m = 0, longitude_sigma_m = 0, height_sigma_m = 0;
  float north_velocity_sigma_mps = 0, east_velocity_sigma_mps = 0, up_velocity_sigma_mps = 0;
  float roll_sigma_deg = 0, pitch_sigma_deg = 0, azimuth_sigma_deg = 0;
  uint32_t extended_status = 0;       // "INS Extended Solution Status" bits
  uint16_t seconds_since_update = 0;  // since the last ZUPT or position update, s

  bool operator==(const InsPvaX&) const = default;
};

// RAWIMUSX: one raw IMU sample in the IMU body frame, as increments since the last sample in the
// IMU's own counts (the velocity and angle scale factors depend on the IMU type). The Y axis is
// sent negated, as the reference documents.
struct RawImuSX {
  Oem7Header header;
  uint8_t imu_info = 0;  // bit 0: an IMU error was detected (see imu_status)
  uint8_t imu_type = 0;  // the OEM7 IMU type table's number
  uint16_t gnss_week = 0;
  double gnss_seconds_of_week = 0;  // the sample's time, s (finer than the header's milliseconds)
  uint32_t imu_status = 0;          // IMU-type-specific status bits
  int32_t accel_z_counts = 0, accel_minus_y_counts = 0, accel_x_counts = 0;  // velocity increments
  int32_t gyro_z_counts = 0, gyro_minus_y_counts = 0, gyro_x_counts = 0;     // angle increments

  bool operator==(const RawImuSX&) const = default;
};

using Oem7Message = std::variant<BestPos, BestVel, InsPvaX, RawImuSX>;

}  // namespace brickyard::drivers
