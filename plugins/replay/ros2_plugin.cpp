// replay.ros2_point_cloud, replay.ros2_gnss_fix, replay.ros2_imu, replay.ros2_odometry: a ROS 2
// bag of a team's own (rosbag2 MCAP: sensor_msgs/msg/PointCloud2, NavSatFix, Imu; nav_msgs/msg/
// Odometry, its localization, as our estimate) replayed in-process as our messages on the run's
// clock, so its drive runs through the perception and the fusion (docs/ros2.md). The
// conversions are bag play --map's (cdr/ros2_to_msgs.hpp). A ROS 2 bag is stamped on the real
// clock: on the sim clock, retime_from_ns is its drive's start (0: a bag of a simulated run). A
// sample that does not fit its type is bad input; one whose bytes end early is skipped, counted.
#include <brickyard/plugin.hpp>

#include "ros2_convert.hpp"  // and the messages it converts into
#include "replay/common/recording.hpp"
#include "replay/common/replay_checks.hpp"
#include "replay/common/sample_queue.hpp"

#include <memory>
#include <optional>

namespace {

using namespace brickyard;

struct Settings {
  std::string file, topic;
  double rate_hz = 1000;
  std::int64_t retime_from_ns = -1;
  int sensor_id = 0;                                                         // ros2_point_cloud
  double mount_x = 0, mount_y = 0, mount_z = 0, mount_roll = 0, mount_pitch = 0, mount_yaw = 0;  // ros2_point_cloud
  int receiver_id = 0;                                                       // ros2_gnss_fix
  drivers::Datum datum;                                                      // ros2_gnss_fix
  cdr::CloudMount mount() const { return {sensor_id, {mount_x, mount_y, mount_z, mount_roll, mount_pitch, mount_yaw}}; }
};

// What every ROS 2 replay reads, and what its message type needs.
template <class T> ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("file", &Settings::file).doc("the ROS 2 bag (rosbag2 MCAP)");
  b.bind("topic", &Settings::topic).doc("the bag's topic, as the bag names it (\"/ouster/points\")");
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(1, 10000).doc("how often due samples are sent");
  b.bind("retime_from_ns", &Settings::retime_from_ns).in_unit("ns").range(-1, 9e18)
      .doc("on the sim clock: every sample's time and stamp less this (the drive's first time; 0 for a bag of a simulated run); -1: off");
  if constexpr (std::is_same_v<T, msgs::PointCloud>) {
    b.bind("sensor_id", &Settings::sensor_id).range(0, 255).doc("our cloud's sensor id");
    // The sensor's pose in the vehicle frame: ROS 2's cloud names only a frame.
    b.bind("mount_x", &Settings::mount_x).in_unit("m").range(-100, 100).doc("the sensor's position in the vehicle frame");
    b.bind("mount_y", &Settings::mount_y).in_unit("m").range(-100, 100).doc("the sensor's position in the vehicle frame");
    b.bind("mount_z", &Settings::mount_z).in_unit("m").range(-100, 100).doc("the sensor's position in the vehicle frame");
    b.bind("mount_roll", &Settings::mount_roll).in_unit("rad").range(-4, 4).doc("the sensor's attitude in the vehicle frame");
    b.bind("mount_pitch", &Settings::mount_pitch).in_unit("rad").range(-4, 4).doc("the sensor's attitude in the vehicle frame");
    b.bind("mount_yaw", &Settings::mount_yaw).in_unit("rad").range(-4, 4).doc("the sensor's attitude in the vehicle frame");
  } else if constexpr (std::is_same_v<T, msgs::GnssFix>) {
    b.bind("receiver_id", &Settings::receiver_id).range(0, 255).doc("our fix's receiver id");
    b.bind_required("datum_latitude", &Settings::datum, &drivers::Datum::latitude_deg).in_unit("deg").range(-90, 90).doc("the map frame's origin");
    b.bind_required("datum_longitude", &Settings::datum, &drivers::Datum::longitude_deg).in_unit("deg").range(-180, 180).doc("the map frame's origin");
    b.bind("datum_altitude", &Settings::datum, &drivers::Datum::height_m).in_unit("m").range(-1000, 10000).doc("above the WGS84 ellipsoid");
  }
  return b;
}

template <class T> struct Ports {
  Output<T> out;
};
template <class T> PortBinding<Ports<T>> ports() {
  PortBinding<Ports<T>> b;
  b.output("out", &Ports<T>::out).doc("the bag's samples as ours, each at its recorded time");
  return b;
}

template <class T, const char* Name, const char* Ros2Type>
class Ros2Replay : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest(std::string("replay.ros2_") + Name, "1.0.0")
        .describe(std::string("replays a ROS 2 bag's ") + Ros2Type + " as " + message_traits<T>::name + " at the times it was recorded")
        .with_ports(ports<T>()).parameters(bindings<T>()).periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    s_ = bindings<T>().read(ctx.params());
    if (s_.file.empty()) throw BadInput("parameter 'file': the ROS 2 bag to replay is required");
    if (s_.topic.empty()) throw BadInput("parameter 'topic': the bag's topic is required");
    convert_.mount = s_.mount();
    convert_.receiver_id = s_.receiver_id;
    if constexpr (std::is_same_v<T, msgs::GnssFix>) convert_.datum.emplace(s_.datum);
    try {
      load(ctx, ctx.find_file(s_.file));
    } catch (const replay::RecordingError& e) {
      throw BadInput(std::string("parameter 'file': ") + e.what());
    }
    io_ = ports<T>().connect(ctx);
  }

  void step(Context& ctx) override {
    samples_.release(ctx.now_ns(), [&](auto&& m) { io_.out.publish(std::move(m)); });
  }

  void deactivate(Context& ctx) override {
    ctx.metric("replayed", static_cast<double>(samples_.sent()));
    ctx.metric("left", static_cast<double>(samples_.left()));
    ctx.metric("damaged_skipped", static_cast<double>(damaged_));
  }

 private:
  void load(Context& ctx, const std::string& file) {
    replay::Recording rec(file);
    const bool retime = s_.retime_from_ns >= 0;
    const std::string clock = rec.metadata("clock").empty() ? "real" : rec.metadata("clock");  // rosbag2 records the wall clock
    if (const std::string e = replay::clock_problem(file, clock, ctx.sim_clock(), retime); !e.empty()) throw BadInput(e);
    const replay::RecordedTopic* t = rec.topic(s_.topic);
    if (!t) throw BadInput(replay::missing_topic(file, rec, s_.topic));
    if (t->type != Ros2Type)
      throw BadInput("bag " + file + ": topic '" + s_.topic + "' holds " + (t->type.empty() ? "no schema" : t->type) + ", this node replays " + Ros2Type);
    std::uint32_t seq = 0;
    for (auto& s : rec.samples(*t)) {  // every sample converted now: a bad one is bad input, found before the run
      auto m = std::make_shared<T>();
      try {
        convert_(s.data, seq, *m);
      } catch (const cdr::DamagedSample& e) {  // one message lost: counted, the first named, skipped
        if (damaged_++ == 0)
          ctx.log(LogLevel::warn, "bag " + file + ": sample " + std::to_string(seq) + " of '" + s_.topic + "' is damaged, skipped: " + e.what());
        ++seq;
        continue;
      } catch (const std::invalid_argument& e) {
        throw BadInput("bag " + file + ": sample " + std::to_string(seq) + " of '" + s_.topic + "': " + e.what());
      }
      ++seq;
      const std::optional<std::int64_t> stamp = replay::retimed(s.stamp_ns, s_.retime_from_ns);
      if (!stamp) continue;
      if (retime) m->header().stamp_ns(m->header().stamp_ns() - s_.retime_from_ns);
      samples_.push(*stamp, std::move(m));
    }
  }

  Settings s_;
  replay::Ros2Converter convert_;
  std::uint64_t damaged_ = 0;
  replay::SampleQueue<std::shared_ptr<const T>> samples_;
  Ports<T> io_;
};

constexpr char kPointCloud[] = "point_cloud", kGnssFix[] = "gnss_fix", kImu[] = "imu", kOdometry[] = "odometry";
constexpr char kPointCloud2[] = "sensor_msgs/msg/PointCloud2", kNavSatFix[] = "sensor_msgs/msg/NavSatFix", kRosImu[] = "sensor_msgs/msg/Imu";
constexpr char kRosOdometry[] = "nav_msgs/msg/Odometry";

}  // namespace

BRICKYARD_PLUGINS(Ros2Replay<msgs::PointCloud, kPointCloud, kPointCloud2>, Ros2Replay<msgs::GnssFix, kGnssFix, kNavSatFix>,
                  Ros2Replay<msgs::Imu, kImu, kRosImu>, Ros2Replay<msgs::LocalizationEstimate, kOdometry, kRosOdometry>)
