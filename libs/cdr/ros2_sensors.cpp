#include "cdr/ros2_sensors.hpp"

#include "cdr/cdr_reader.hpp"
#include "cdr/cdr_writer.hpp"

namespace brickyard::cdr {

NavSatFixValues read_navsatfix(const unsigned char* cdr, std::size_t size) {
  CdrReader r(cdr, size, "NavSatFix");
  NavSatFixValues v;
  v.stamp_ns = r.time_ns("header.stamp");
  v.frame_id = r.string("header.frame_id");
  v.status = r.get<std::int8_t>("status.status");
  v.service = r.get<std::uint16_t>("status.service");
  v.latitude = r.get<double>("latitude");
  v.longitude = r.get<double>("longitude");
  v.altitude = r.get<double>("altitude");
  for (double& c : v.position_covariance) c = r.get<double>("position_covariance");
  v.covariance_type = r.get<std::uint8_t>("position_covariance_type");
  return v;
}

ImuValues read_imu(const unsigned char* cdr, std::size_t size) {
  CdrReader r(cdr, size, "Imu");
  ImuValues v;
  v.stamp_ns = r.time_ns("header.stamp");
  v.frame_id = r.string("header.frame_id");
  for (double& q : v.orientation) q = r.get<double>("orientation");
  for (int i = 0; i < 9; ++i) r.get<double>("orientation_covariance");
  for (double& w : v.angular_velocity) w = r.get<double>("angular_velocity");
  for (int i = 0; i < 9; ++i) r.get<double>("angular_velocity_covariance");
  for (double& a : v.linear_acceleration) a = r.get<double>("linear_acceleration");
  for (int i = 0; i < 9; ++i) r.get<double>("linear_acceleration_covariance");
  return v;
}

void write_navsatfix(const NavSatFixValues& v, std::vector<unsigned char>& out) {
  CdrWriter w(out);
  w.put_header(v.stamp_ns, v.frame_id);
  w.put<std::int8_t>(v.status);
  w.put<std::uint16_t>(v.service);
  w.put<double>(v.latitude);
  w.put<double>(v.longitude);
  w.put<double>(v.altitude);
  for (double c : v.position_covariance) w.put<double>(c);
  w.put<std::uint8_t>(v.covariance_type);
}

void write_imu(const ImuValues& v, std::vector<unsigned char>& out) {
  CdrWriter w(out);
  w.put_header(v.stamp_ns, v.frame_id);
  for (double q : v.orientation) w.put<double>(q);
  for (int i = 0; i < 9; ++i) w.put<double>(i == 0 && !v.has_orientation ? -1.0 : 0.0);  // REP 145: -1, no orientation
  for (double a : v.angular_velocity) w.put<double>(a);
  for (int i = 0; i < 9; ++i) w.put<double>(0.0);  // 0: covariance unknown
  for (double a : v.linear_acceleration) w.put<double>(a);
  for (int i = 0; i < 9; ++i) w.put<double>(0.0);
}

}  // namespace brickyard::cdr
