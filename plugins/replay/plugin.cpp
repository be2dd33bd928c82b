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

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>

#include "common/recording.hpp"

#include "cloud/quantized_cloud.hpp"

#include <cstring>
#include <memory>
#include <type_traits>
#include <vector>

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

// Decodes one recorded sample as Fast DDS would; when the bytes do not fit the type, says how many
// did (a damaged sample was "Cdr::read_encapsulation", with no place).
template <class T> std::string decode(const std::vector<unsigned char>& data, T& m) {
  std::vector<char> bytes(data.begin(), data.end());  // fastcdr reads through a mutable buffer
  eprosima::fastcdr::FastBuffer buffer(bytes.data(), bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
  try {
    cdr.read_encapsulation();
    m.deserialize(cdr);
  } catch (const eprosima::fastcdr::exception::Exception& e) {
    return "its first " + std::to_string(cdr.getSerializedDataLength()) + " of " + std::to_string(data.size()) +
           " bytes decode, the next do not (" + e.what() + ")";
  }
  return {};
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
        .with_ports(ports<T>())
        .parameters(bindings())
        .periodic("rate_hz");
  }

  void configure(Context& ctx) override {
    s_ = bindings().read(ctx.params());
    const Settings& s = s_;
    const std::string& topic = s.topic;
    if (s.file.empty()) throw BadInput("parameter 'file': the recording to replay is required");
    if (topic.empty()) throw BadInput("parameter 'topic': the recorded topic (NODE.PORT) is required");
    const std::string file = ctx.find_file(s.file);
    try {
      replay::Recording rec(file);
      // Stamps are the recording run's clock: sim time from 0, or the epoch on the real clock.
      const std::string clock = rec.metadata("clock");
      const bool retime = s.retime_from_ns >= 0;
      if (retime && !(clock == "real" && ctx.sim_clock()))
        throw BadInput("parameter 'retime_from_ns': re-times a real-clock recording onto the sim clock; " + file + " was made on the " +
                       (clock.empty() ? "unknown" : clock) + " clock and this run is on the " + (ctx.sim_clock() ? "sim" : "real") + " clock");
      if (!retime && clock != (ctx.sim_clock() ? "sim" : "real"))
        throw BadInput("recording " + file + " was made on the " + (clock.empty() ? "unknown" : clock) + " clock, this run is on the " +
                       (ctx.sim_clock() ? "sim" : "real") + " clock: its samples' times would not line up");
      const replay::RecordedTopic* t = rec.topic(topic);
      if (!t) {
        std::string have;
        for (const auto& x : rec.topics()) have += (have.empty() ? "" : ", ") + x.name;
        throw BadInput("recording " + file + " has no topic '" + topic + "' (it has: " + have + ")");
      }
      // A cloud recorded compact (--record-cloud-precision) is replayed as the PointCloud it was.
      bool packed = false;
      if constexpr (std::is_same_v<T, msgs::PointCloud>) packed = t->type == message_traits<msgs::QuantizedPointCloud>::name;
      const std::string& want = packed ? message_traits<msgs::QuantizedPointCloud>::name : message_traits<T>::name;
      const std::string& want_hash = packed ? message_traits<msgs::QuantizedPointCloud>::hash : message_traits<T>::hash;
      if (t->type != want)
        throw BadInput("recording " + file + ": topic '" + topic + "' holds " + t->type + ", this node replays " +
                       message_traits<T>::name + " (use the replay plugin of that type)");
      if (t->type_hash != want_hash)
        throw BadInput("recording " + file + ": topic '" + topic + "' was recorded with another definition of " + t->type +
                       " (IDL hash " + t->type_hash + ", this build " + want_hash + ")");
      // Every sample decoded now: a bad one is bad input, found before the run starts.
      for (auto& s : rec.samples(*t)) {
        auto m = std::make_shared<T>();
        std::string e;
        if constexpr (std::is_same_v<T, msgs::PointCloud>) {
          if (packed) {
            msgs::QuantizedPointCloud q;
            e = decode(s.data, q);
            try {
              if (e.empty()) *m = cloud::unpack<msgs::PointCloud>(q);
            } catch (const std::invalid_argument& x) {
              e = x.what();
            }
          }
        }
        if (!packed) e = decode(s.data, *m);
        if (!e.empty())
          throw BadInput("recording " + file + ": sample " + std::to_string(samples_.size()) + " of '" + topic + "' does not decode as " +
                         want + ": " + e);
        std::int64_t stamp = s.stamp_ns;
        if (retime) {  // the drive from 0: the sample's time and its measurement's stamp alike
          if (stamp < s_.retime_from_ns) continue;
          stamp -= s_.retime_from_ns;
          m->header().stamp_ns(m->header().stamp_ns() - s_.retime_from_ns);
        }
        samples_.push_back({stamp, std::move(m)});
      }
    } catch (const replay::RecordingError& e) {
      throw BadInput(std::string("parameter 'file': ") + e.what());
    }
    io_ = ports<T>().connect(ctx);
  }

  void step(Context& ctx) override {
    const std::int64_t now = ctx.now_ns();
    for (; next_ < samples_.size() && samples_[next_].stamp_ns <= now; ++next_)
      io_.out.publish(std::move(samples_[next_].message));  // published: this node lets go of it
  }

  void deactivate(Context& ctx) override {
    ctx.metric("replayed", static_cast<double>(next_));
    ctx.metric("left", static_cast<double>(samples_.size() - next_));
  }

 private:
  struct Sample {
    std::int64_t stamp_ns;
    std::shared_ptr<const T> message;
  };
  Settings s_;
  std::vector<Sample> samples_;
  std::size_t next_ = 0;
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
