#include "cdr/ros2_sensors.hpp"

#include "cdr/cdr_reader.hpp"

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

}  // namespace brickyard::cdr
