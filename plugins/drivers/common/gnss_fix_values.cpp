#include "gnss_fix_values.hpp"

#include <cmath>

namespace brickyard::drivers {

namespace {

// The header's time when the receiver knows GPS time (from "fine" on the time status scale of the
// OEM7 reference: coarse times can be off by more than a LiDAR frame).
std::optional<int64_t> header_time(const Oem7Header& h) {
  if (static_cast<int>(h.time_status) < static_cast<int>(TimeStatus::fine_adjusting)) return std::nullopt;
  return (static_cast<int64_t>(h.week) * 604800000 + h.milliseconds) * 1000000;
}

bool finite_position(double lat, double lon, double h) {
  return std::isfinite(lat) && std::isfinite(lon) && std::isfinite(h) && std::abs(lat) <= 90 && std::abs(lon) <= 180;
}

void place(GnssFixValues& f, const LocalDatum& datum, double lat, double lon, double height) {
  const Eigen::Vector3d p = datum.to_map({lat, lon, height});
  f.x = p.x(), f.y = p.y(), f.z = p.z();
}

}  // namespace

uint8_t fix_type_of(PositionType type) {
  switch (type) {
    case PositionType::none: return 0;
    case PositionType::l1_int: case PositionType::wide_int: case PositionType::narrow_int:
    case PositionType::rtk_direct_ins: case PositionType::ins_rtkfixed: return 3;
    case PositionType::l1_float: case PositionType::ionofree_float: case PositionType::narrow_float:
    case PositionType::ins_rtkfloat: return 2;
    default: return 1;
  }
}

uint8_t fix_type_of_gga(int quality) {
  switch (quality) {
    case 4: return 3;
    case 5: return 2;
    case 1: case 2: case 6: case 9: return 1;
    default: return 0;
  }
}

std::optional<GnssFixValues> fix_from(const BestPos& m, const LocalDatum& datum) {
  if (m.datum_id != kDatumWgs84) return std::nullopt;
  const double height = m.height_msl_m + m.undulation_m;
  if (!finite_position(m.latitude_deg, m.longitude_deg, height)) return std::nullopt;
  GnssFixValues f;
  place(f, datum, m.latitude_deg, m.longitude_deg, height);
  f.sigma_x = m.longitude_sigma_m, f.sigma_y = m.latitude_sigma_m, f.sigma_z = m.height_sigma_m;
  f.valid = m.solution_status == SolutionStatus::computed && m.position_type != PositionType::none;
  f.fix_type = f.valid ? fix_type_of(m.position_type) : 0;
  f.device_time_ns = header_time(m.header);
  return f;
}

std::optional<GnssFixValues> fix_from(const InsPvaX& m, const LocalDatum& datum) {
  const double height = m.height_msl_m + m.undulation_m;
  if (!finite_position(m.latitude_deg, m.longitude_deg, height)) return std::nullopt;
  GnssFixValues f;
  place(f, datum, m.latitude_deg, m.longitude_deg, height);
  f.sigma_x = m.longitude_sigma_m, f.sigma_y = m.latitude_sigma_m, f.sigma_z = m.height_sigma_m;
  f.valid = (m.ins_status == InsStatus::solution_good || m.ins_status == InsStatus::solution_free) &&
            m.position_type != PositionType::none;
  f.fix_type = f.valid ? fix_type_of(m.position_type) : 0;
  f.device_time_ns = header_time(m.header);
  return f;
}

std::optional<GnssFixValues> fix_from(const NmeaGga& m, const LocalDatum& datum, const GgaSigmas& sigmas) {
  if (!m.latitude_deg || !m.longitude_deg || !m.hdop) return std::nullopt;
  const double height = m.altitude_msl_m.value_or(0) + m.undulation_m.value_or(0);
  if (!finite_position(*m.latitude_deg, *m.longitude_deg, height) || !std::isfinite(*m.hdop) || *m.hdop < 0) return std::nullopt;
  GnssFixValues f;
  place(f, datum, *m.latitude_deg, *m.longitude_deg, height);
  f.fix_type = fix_type_of_gga(m.quality);
  f.valid = f.fix_type > 0 && m.altitude_msl_m.has_value();
  const double error = f.fix_type == 3 ? sigmas.rtk_fixed_m : f.fix_type == 2 ? sigmas.rtk_float_m
                       : m.quality == 2 || m.quality == 9 ? sigmas.differential_m : sigmas.single_m;
  f.sigma_x = f.sigma_y = *m.hdop * error;
  f.sigma_z = 2 * f.sigma_x;
  if (m.utc) f.device_time_ns = (m.utc->hours * 3600 + m.utc->minutes * 60) * int64_t{1000000000} + std::llround(m.utc->seconds * 1e9);
  return f;
}

namespace {
double day_seconds(const NmeaTime& t) { return t.hours * 3600.0 + t.minutes * 60.0 + t.seconds; }
// b - a, across midnight: within half a day.
double day_difference(double a, double b) { return std::remainder(b - a, 86400.0); }
constexpr double kSameTime_s = 1e-3;
}  // namespace

void GstSigmas::gst(const NmeaGst& m) {
  if (!m.utc || !m.latitude_sigma_m || !m.longitude_sigma_m || !m.height_sigma_m) return;
  gst_ = m;
  gst_s_ = day_seconds(*m.utc);
}

bool GstSigmas::apply(const NmeaGga& gga, GnssFixValues& f) {
  if (!gga.utc) return false;
  const double t = day_seconds(*gga.utc);
  bool serves = false;
  if (gst_) {
    const double age = day_difference(*gst_s_, t);
    const bool same_epoch = std::abs(age) < kSameTime_s;
    const bool epoch_before = last_gga_s_ && std::abs(day_difference(*last_gga_s_, *gst_s_)) < kSameTime_s &&
                              last_gga_fix_type_ == f.fix_type && age > 0 && age <= max_age_s_;
    serves = same_epoch || epoch_before;
  }
  if (serves) f.sigma_x = *gst_->longitude_sigma_m, f.sigma_y = *gst_->latitude_sigma_m, f.sigma_z = *gst_->height_sigma_m;
  last_gga_s_ = t;
  last_gga_fix_type_ = f.fix_type;
  return serves;
}

}  // namespace brickyard::drivers
