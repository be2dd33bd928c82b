// replay.<type>: republishes one recorded topic (`brickyard run --record`) on the run's clock —
// every sample at the time it was first published — so a perception or estimation graph can be
// rerun on recorded data. One plugin per message type (the port's type is the manifest's), e.g.
// replay.gnss_fix, replay.imu, replay.point_cloud. Reading: common/recording.hpp.
#include <brickyard/plugin.hpp>

#include <brickyard/msgs/BlobPubSubTypes.h>
#include <brickyard/msgs/ClusterListPubSubTypes.h>
#include <brickyard/msgs/ControlCommandPubSubTypes.h>
#include <brickyard/msgs/GnssFixPubSubTypes.h>
#include <brickyard/msgs/ImuPubSubTypes.h>
#include <brickyard/msgs/LocalizationEstimatePubSubTypes.h>
#include <brickyard/msgs/ModeStatusPubSubTypes.h>
#include <brickyard/msgs/ObstacleListPubSubTypes.h>
#include <brickyard/msgs/PathPubSubTypes.h>
#include <brickyard/msgs/PointCloudPubSubTypes.h>
#include <brickyard/msgs/QuantizedPointCloudPubSubTypes.h>
#include <brickyard/msgs/ScalarPubSubTypes.h>
#include <brickyard/msgs/TrackWorldPubSubTypes.h>
#include <brickyard/msgs/VehicleStatePubSubTypes.h>
#include <brickyard/msgs/WallEstimatePubSubTypes.h>
#include <brickyard/msgs/WheelSpeedsPubSubTypes.h>

#include "replay/common/recording.hpp"
#include "replay/common/replay_checks.hpp"
#include "replay/common/sample_queue.hpp"
#include "sample_decode.hpp"

#include <memory>
#include <optional>
#include <type_traits>

namespace {

using namespace brickyard;

struct Settings {
  std::string file, topic;
  double rate_hz = 1000;
  std::int64_t retime_from_ns = -1;
};

ParamBinding<Settings> bindings() {
  ParamBinding<Settings> b;
  b.bind("file", &Settings::file).doc("the recording (brickyard run --record FILE)");
  b.bind("topic", &Settings::topic).doc("the recorded topic, NODE.PORT as in the recording");
  b.bind("rate_hz", &Settings::rate_hz).in_unit("Hz").range(1, 10000).doc("how often due samples are sent");
  b.bind("retime_from_ns", &Settings::retime_from_ns)
      .in_unit("ns")
      .range(-1, 9e18)  // a real-clock recording's first time: Unix ns (int64 holds up to 9.2e18)
      .doc("a real-clock recording on the sim clock: every sample's time and header stamp less this (the recording's "
           "first time, brickyard map build gives it), so the drive starts at 0; -1: off");
  return b;
}

template <class T> struct Ports {
  Output<T> out;
};

template <class T> PortBinding<Ports<T>> ports() {
  PortBinding<Ports<T>> b;
  b.output("out", &Ports<T>::out).doc("the recorded samples, each at its recorded time");
  return b;
}

template <class T, class PubSub, const char* Name>
class Replay : public Plugin {
 public:
  static Manifest manifest() {
    return Manifest(std::string("replay.") + Name, "1.0.0")
        .describe(std::string("republishes a recorded topic of ") + message_traits<T>::name + " at the times it was published")
        .with_ports(ports<T>()).parameters(bindings()).periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    s_ = bindings().read(ctx.params());
    if (s_.file.empty()) throw BadInput("parameter 'file': the recording to replay is required");
    if (s_.topic.empty()) throw BadInput("parameter 'topic': the recorded topic (NODE.PORT) is required");
    const std::string file = ctx.find_file(s_.file);
    try {
      load(ctx, file);
    } catch (const replay::RecordingError& e) {
      throw BadInput(std::string("parameter 'file': ") + e.what());
    }
    io_ = ports<T>().connect(ctx);
  }

  void step(Context& ctx) override {
    samples_.release(ctx.now_ns(), [&](auto&& m) { io_.out.publish(std::move(m)); });  // published: this node lets go of it
  }

  void deactivate(Context& ctx) override {
    ctx.metric("replayed", static_cast<double>(samples_.sent()));
    ctx.metric("left", static_cast<double>(samples_.left()));
  }

 private:
  using Packed = msgs::QuantizedPointCloud;

  void load(Context& ctx, const std::string& file) {
    replay::Recording rec(file);
    const bool retime = s_.retime_from_ns >= 0;
    if (const std::string e = replay::clock_problem(file, rec.metadata("clock"), ctx.sim_clock(), retime); !e.empty()) throw BadInput(e);
    const replay::RecordedTopic* t = rec.topic(s_.topic);
    if (!t) throw BadInput(replay::missing_topic(file, rec, s_.topic));
    // A cloud recorded compact (--record-cloud-precision) is replayed as the PointCloud it was.
    const bool packed = std::is_same_v<T, msgs::PointCloud> && t->type == message_traits<Packed>::name;
    const std::string want = packed ? message_traits<Packed>::name : message_traits<T>::name;
    const std::string want_hash = packed ? message_traits<Packed>::hash : message_traits<T>::hash;
    if (const std::string e = replay::type_problem(file, s_.topic, *t, want, want_hash, message_traits<T>::name); !e.empty())
      throw BadInput(e);
    // Every sample decoded now: a bad one is bad input, found before the run starts.
    for (auto& s : rec.samples(*t)) {
      auto m = std::make_shared<T>();
      if (const std::string e = replay::decode_sample(s.data, packed, *m); !e.empty())
        throw BadInput("recording " + file + ": sample " + std::to_string(samples_.size()) + " of '" + s_.topic + "' does not decode as " +
                       want + ": " + e);
      const std::optional<std::int64_t> stamp = replay::retimed(s.stamp_ns, s_.retime_from_ns);
      if (!stamp) continue;  // before the drive's start
      if (retime) m->header().stamp_ns(m->header().stamp_ns() - s_.retime_from_ns);  // the measurement's stamp alike
      samples_.push(*stamp, std::move(m));
    }
  }

  Settings s_;
  replay::SampleQueue<std::shared_ptr<const T>> samples_;
  Ports<T> io_;
};

constexpr char kBlob[] = "blob", kClusterList[] = "cluster_list", kControlCommand[] = "control_command",
               kGnssFix[] = "gnss_fix", kImu[] = "imu", kLocalizationEstimate[] = "localization_estimate",
               kModeStatus[] = "mode_status", kObstacleList[] = "obstacle_list", kPath[] = "path",
               kPointCloud[] = "point_cloud", kScalar[] = "scalar", kTrackWorld[] = "track_world",
               kVehicleState[] = "vehicle_state", kWallEstimate[] = "wall_estimate", kWheelSpeeds[] = "wheel_speeds";

using namespace brickyard::msgs;

}  // namespace

BRICKYARD_PLUGINS(Replay<Blob, BlobPubSubType, kBlob>, Replay<ClusterList, ClusterListPubSubType, kClusterList>,
                  Replay<ControlCommand, ControlCommandPubSubType, kControlCommand>,
                  Replay<GnssFix, GnssFixPubSubType, kGnssFix>, Replay<Imu, ImuPubSubType, kImu>,
                  Replay<LocalizationEstimate, LocalizationEstimatePubSubType, kLocalizationEstimate>,
                  Replay<ModeStatus, ModeStatusPubSubType, kModeStatus>,
                  Replay<ObstacleList, ObstacleListPubSubType, kObstacleList>, Replay<Path, PathPubSubType, kPath>,
                  Replay<PointCloud, PointCloudPubSubType, kPointCloud>, Replay<Scalar, ScalarPubSubType, kScalar>,
                  Replay<TrackWorld, TrackWorldPubSubType, kTrackWorld>,
                  Replay<VehicleState, VehicleStatePubSubType, kVehicleState>,
                  Replay<WallEstimate, WallEstimatePubSubType, kWallEstimate>,
                  Replay<WheelSpeeds, WheelSpeedsPubSubType, kWheelSpeeds>)
