// Our messages as ROS 2's standard ones (ros2/bridge/to_ros2.hpp), each written as its CDR and read
// back by ROS 2 Humble's definitions (cdr/ros2_std_types.hpp) through the generic CDR reader: the
// values, frames and layout a ROS 2 node would read. (evidence.ros2_bridge reads them with
// Foxglove's ROS 2 decoder and ROS 2's own definitions.)
#include "ros2/bridge/to_ros2.hpp"

#include "cdr/cdr_json.hpp"
#include "cdr/ros2_std_types.hpp"
#include "cdr/ros2_to_msgs.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace brickyard;

namespace {

nlohmann::json read_as(const std::string& type, const std::vector<unsigned char>& cdr) {
  return cdr::CdrJson(cdr::self_contained_idl(cdr::ros2_standard_idl(type))).decode(type, cdr.data(), cdr.size());
}

msgs::LocalizationEstimate estimate() {
  msgs::LocalizationEstimate e;
  e.header().stamp_ns(12'250'000'000);
  e.header().frame_id("map");
  e.x(101.5);
  e.y(-7.25);
  e.yaw(0.5);
  e.speed(61.0);
  e.yaw_rate(0.05);
  e.covariance({0.04, 0.001, 0.002, 0.001, 0.09, 0.003, 0.002, 0.003, 0.0004});
  return e;
}

}  // namespace

TEST(Ros2Bridge, AnEstimateIsOdometryOfTheBaseInTheMap) {
  std::vector<unsigned char> cdr;
  cdr::write_odometry(ros2::odometry(estimate(), ros2::Frames{}), cdr);
  const auto o = read_as("nav_msgs::msg::Odometry", cdr);
  EXPECT_EQ(o["header"]["stamp"]["sec"], 12);
  EXPECT_EQ(o["header"]["stamp"]["nanosec"], 250000000);
  EXPECT_EQ(o["header"]["frame_id"], "map");
  EXPECT_EQ(o["child_frame_id"], "base_link");
  const auto& pose = o["pose"]["pose"];
  EXPECT_EQ(pose["position"]["x"], 101.5);
  EXPECT_EQ(pose["position"]["y"], -7.25);
  EXPECT_EQ(pose["position"]["z"], 0.0);
  EXPECT_NEAR(pose["orientation"]["z"].get<double>(), std::sin(0.25), 1e-15);
  EXPECT_NEAR(pose["orientation"]["w"].get<double>(), std::cos(0.25), 1e-15);
  EXPECT_EQ(pose["orientation"]["x"], 0.0);
  const auto& c = o["pose"]["covariance"];
  ASSERT_EQ(c.size(), 36u);
  EXPECT_EQ(c[0], 0.04);     // x x
  EXPECT_EQ(c[1], 0.001);    // x y
  EXPECT_EQ(c[5], 0.002);    // x yaw
  EXPECT_EQ(c[30], 0.002);   // yaw x
  EXPECT_EQ(c[35], 0.0004);  // yaw yaw
  EXPECT_EQ(c[7], 0.09);     // y y
  EXPECT_EQ(c[14], 1e6);     // z: not estimated
  EXPECT_EQ(c[2], 0.0);
  EXPECT_EQ(o["twist"]["twist"]["linear"]["x"], 61.0);
  EXPECT_EQ(o["twist"]["twist"]["angular"]["z"], 0.05);
}

TEST(Ros2Bridge, AnEstimateIsAPoseAndTheMapToBaseTransform) {
  ros2::Frames f;
  f.map = "track";
  std::vector<unsigned char> cdr;
  const auto odom = ros2::odometry(estimate(), f);
  cdr::write_pose_stamped(odom.stamp_ns, odom.frame_id, odom.pose, cdr);
  const auto p = read_as("geometry_msgs::msg::PoseStamped", cdr);
  EXPECT_EQ(p["header"]["frame_id"], "track");
  EXPECT_EQ(p["pose"]["position"]["x"], 101.5);
  cdr::write_tf_message({ros2::map_to_base(estimate(), f)}, cdr);
  const auto tf = read_as("tf2_msgs::msg::TFMessage", cdr);
  ASSERT_EQ(tf["transforms"].size(), 1u);
  EXPECT_EQ(tf["transforms"][0]["header"]["frame_id"], "track");
  EXPECT_EQ(tf["transforms"][0]["child_frame_id"], "base_link");
  EXPECT_EQ(tf["transforms"][0]["transform"]["translation"]["y"], -7.25);
  EXPECT_NEAR(tf["transforms"][0]["transform"]["rotation"]["z"].get<double>(), std::sin(0.25), 1e-15);
}

TEST(Ros2Bridge, ACloudIsAPointCloud2InItsSensorsFrameAndItsMountATransform) {
  msgs::PointCloud c;
  c.header().stamp_ns(3'000'000'001);
  c.header().frame_id("lidar_front");
  c.sensor_id(0);
  c.sensor_x(1.5);
  c.sensor_z(1.1);
  c.sensor_yaw(M_PI / 2);
  c.x({1, 2, 3});
  c.y({4, 5, 6});
  c.z({-1, -1, -1});
  c.intensity({10, 20, 30});
  ros2::Frames f;
  cdr::CloudColumns cols;
  ros2::cloud_columns(c, f, cols);
  std::vector<unsigned char> cdr;
  cdr::write_pointcloud2(cols, cdr);
  const auto back = cdr::read_pointcloud2(cdr.data(), cdr.size());
  EXPECT_EQ(back.frame_id, "lidar_front");
  EXPECT_EQ(back.stamp_ns, 3'000'000'001);
  EXPECT_EQ(back.x, c.x());
  EXPECT_EQ(back.intensity, c.intensity());
  cdr::write_tf_message({ros2::base_to_sensor(c, f)}, cdr);
  const auto tf = read_as("tf2_msgs::msg::TFMessage", cdr)["transforms"][0];
  EXPECT_EQ(tf["header"]["frame_id"], "base_link");
  EXPECT_EQ(tf["child_frame_id"], "lidar_front");
  EXPECT_EQ(tf["transform"]["translation"]["x"], 1.5);
  EXPECT_EQ(tf["transform"]["translation"]["z"], 1.1);
  EXPECT_NEAR(tf["transform"]["rotation"]["z"].get<double>(), std::sqrt(0.5), 1e-15);
  c.header().frame_id("vehicle");  // a cloud without a frame of its own: its sensor's id names one
  EXPECT_EQ(ros2::cloud_frame(c, f), "lidar_0");
}

TEST(Ros2Bridge, APathIsALineStripAndObstaclesAreBoxesAfterADeleteAll) {
  msgs::Path p;
  p.header().frame_id("map");
  p.poses().resize(3);
  for (int i = 0; i < 3; ++i) p.poses()[i].x(10.0 * i), p.poses()[i].y(-i);
  std::vector<unsigned char> cdr;
  ros2::Frames f;
  cdr::write_marker_array(ros2::path_markers(p, f), cdr);
  const auto path = read_as("visualization_msgs::msg::MarkerArray", cdr)["markers"];
  ASSERT_EQ(path.size(), 1u);
  EXPECT_EQ(path[0]["type"], 4);  // LINE_STRIP
  EXPECT_EQ(path[0]["header"]["frame_id"], "map");
  ASSERT_EQ(path[0]["points"].size(), 3u);
  EXPECT_EQ(path[0]["points"][2]["x"], 20.0);
  EXPECT_EQ(path[0]["points"][2]["y"], -2.0);
  EXPECT_GT(path[0]["color"]["a"].get<double>(), 0.0) << "an alpha of 0 draws nothing";

  msgs::ObstacleList o;
  o.header().frame_id("vehicle");
  o.obstacles().resize(2);
  o.obstacles()[1].x(30);
  o.obstacles()[1].size_x(0.6);
  cdr::write_marker_array(ros2::obstacle_markers(o, f), cdr);
  const auto boxes = read_as("visualization_msgs::msg::MarkerArray", cdr)["markers"];
  ASSERT_EQ(boxes.size(), 3u);
  EXPECT_EQ(boxes[0]["action"], 3);  // DELETEALL: the last frame's boxes gone
  EXPECT_EQ(boxes[2]["type"], 1);    // CUBE
  EXPECT_EQ(boxes[2]["id"], 1);
  EXPECT_EQ(boxes[2]["header"]["frame_id"], "base_link");
  EXPECT_EQ(boxes[2]["pose"]["position"]["x"], 30.0);
  EXPECT_EQ(boxes[2]["scale"]["x"], 0.6);
}

TEST(Ros2Bridge, AnImuSampleSaysItHasNoOrientation) {
  msgs::Imu m;
  m.header().stamp_ns(5);
  m.header().frame_id("vehicle");
  m.gyro_z(0.3);
  m.accel_x(-2.5);
  cdr::ImuValues v;
  ros2::imu_values(m, ros2::Frames{}, v);
  std::vector<unsigned char> cdr;
  cdr::write_imu(v, cdr);
  const auto imu = read_as("sensor_msgs::msg::Imu", cdr);
  EXPECT_EQ(imu["header"]["frame_id"], "base_link");
  EXPECT_EQ(imu["header"]["stamp"]["nanosec"], 5);
  EXPECT_EQ(imu["orientation_covariance"][0], -1.0);
  EXPECT_EQ(imu["angular_velocity"]["z"], 0.3);
  EXPECT_EQ(imu["linear_acceleration"]["x"], -2.5);
  const auto back = cdr::read_imu(cdr.data(), cdr.size());
  EXPECT_EQ(back.angular_velocity[2], 0.3);
}

TEST(Ros2Bridge, FramesAreNamedAsRep105NamesThem) {
  ros2::Frames f;
  EXPECT_EQ(f.of("map"), "map");
  EXPECT_EQ(f.of("vehicle"), "base_link");
  EXPECT_EQ(f.of(""), "base_link");
  EXPECT_EQ(f.of("lidar_left"), "lidar_left");
}

// The other way (bag play --map, replay.ros2_odometry): a team's odometry read into our estimate;
// the bridge's own odometry comes back as the estimate it was made of; bytes cut short are named.
TEST(Ros2Bridge, OdometryReadBackIsTheEstimateItWasMadeOf) {
  std::vector<unsigned char> cdr;
  cdr::write_odometry(ros2::odometry(estimate(), ros2::Frames{}), cdr);
  msgs::LocalizationEstimate back;
  cdr::to_estimate(cdr::read_odometry(cdr.data(), cdr.size()), 7, back);
  const auto e = estimate();
  EXPECT_EQ(back.header().stamp_ns(), e.header().stamp_ns());
  EXPECT_EQ(back.header().seq(), 7u);
  EXPECT_EQ(back.header().frame_id(), "map");
  EXPECT_EQ(back.x(), e.x());
  EXPECT_EQ(back.y(), e.y());
  EXPECT_NEAR(back.yaw(), e.yaw(), 1e-15);
  EXPECT_EQ(back.speed(), e.speed());
  EXPECT_EQ(back.yaw_rate(), e.yaw_rate());
  EXPECT_EQ(back.covariance(), e.covariance());
  EXPECT_EQ(back.status(), 0);
  try {
    (void)cdr::read_odometry(cdr.data(), 100);
    FAIL() << "a cut odometry was read";
  } catch (const cdr::DamagedSample& d) {
    EXPECT_NE(std::string(d.what()).find("Odometry: pose.covariance at byte 100 runs past the sample's 100 bytes"), std::string::npos) << d.what();
  }
}

// A fix about the map frame's datum: back where it was (GeographicLib both ways), its sigmas the
// diagonal, its fix type as NavSatStatus says it (bag play reads GBAS back as fixed RTK).
TEST(Ros2Bridge, AFixIsANavSatFixAboutTheDatum) {
  const drivers::LocalDatum datum(drivers::Datum{39.7930, -86.2389, 220.0});
  msgs::GnssFix f;
  f.header().stamp_ns(2'000'000'000);
  f.header().frame_id("gnss_left");
  f.x(120.5), f.y(-340.25), f.z(1.5);
  f.sigma_x(0.02), f.sigma_y(0.03), f.sigma_z(0.05);
  f.fix_type(3);
  f.valid(true);
  cdr::NavSatFixValues v;
  ros2::navsatfix_values(f, datum, ros2::Frames{}, v);
  std::vector<unsigned char> cdr;
  cdr::write_navsatfix(v, cdr);
  const auto back = cdr::read_navsatfix(cdr.data(), cdr.size());
  const Eigen::Vector3d enu = datum.to_map({back.latitude, back.longitude, back.altitude});
  EXPECT_NEAR(enu.x(), 120.5, 1e-6);
  EXPECT_NEAR(enu.y(), -340.25, 1e-6);
  EXPECT_NEAR(enu.z(), 1.5, 1e-6);
  EXPECT_EQ(back.frame_id, "gnss_left");
  EXPECT_EQ(back.status, 2);
  EXPECT_EQ(back.service, 1);
  EXPECT_NEAR(back.position_covariance[4], 0.03 * 0.03, 1e-18);
  EXPECT_EQ(back.position_covariance[1], 0.0);
  EXPECT_EQ(back.covariance_type, 2);
  EXPECT_EQ(cdr::fix_type_of(back.status), 3);
  f.header().frame_id("map");  // ours names the map: the antenna's frame by the receiver
  f.receiver_id(1);
  ros2::navsatfix_values(f, datum, ros2::Frames{}, v);
  EXPECT_EQ(v.frame_id, "gnss_1");
  f.fix_type(2);  // float RTK: a plain fix, never claimed fixed
  ros2::navsatfix_values(f, datum, ros2::Frames{}, v);
  EXPECT_EQ(v.status, 0);
  f.valid(false);
  ros2::navsatfix_values(f, datum, ros2::Frames{}, v);
  EXPECT_EQ(v.status, -1);
}
