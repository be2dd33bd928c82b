// An output's tap: what a sample does besides reaching its readers — recorded (--record, --out),
// sent to the live view's clients and drawn in its scene (--live). Serialized once for both; a
// point cloud recorded compact (--record-cloud-precision, libs/cloud/quantized_cloud.hpp). A
// failed write stops the run; it must not unwind through the publishing plugin.
#include "exec/executive.hpp"
#include "exec/node_runtime.hpp"
#include "live/live_server.hpp"
#include "live/scene.hpp"
#include "record/recorder.hpp"
#include "record/sample_serializer.hpp"

#include "cloud/quantized_cloud.hpp"

#include <brickyard/msgs/PointCloud.h>
#include <brickyard/msgs/QuantizedPointCloud.h>

#include <algorithm>
#include <chrono>
#include <mutex>

namespace brickyard::fw {
namespace {

using Clock = std::chrono::steady_clock;
const std::string& kCloud = message_traits<msgs::PointCloud>::name;
const std::string& kPackedCloud = message_traits<msgs::QuantizedPointCloud>::name;

struct Tap {
  explicit Tap(const std::string& type) : serializer(type) {}
  SampleSerializer serializer;
  std::unique_ptr<SampleSerializer> packed;  // the compact cloud's, for the recording
  std::mutex m;
};

}  // namespace

// What the scenes (the live view's, the recording's) draw of a sample of this topic: none, either, or both.
std::function<void(const void*, std::uint64_t)> Executive::scene_handler(const std::string& topic, const std::string& type) {
  using Handler = std::function<void(const void*, std::uint64_t)>;
  Handler live = scene_ ? scene_->handler(topic, type) : Handler(), recorded = recorded_scene_ ? recorded_scene_->handler(topic, type) : Handler();
  if (!live || !recorded) return live ? live : recorded;
  return [live, recorded](const void* m, std::uint64_t ns) {
    live(m, ns);
    recorded(m, ns);
  };
}

void Executive::tap_output(OutputPort& out, const std::string& topic, const std::string& type) {
  const bool skip = std::find(opt_.record_skip_types.begin(), opt_.record_skip_types.end(), type) != opt_.record_skip_types.end();
  const bool pack_cloud = opt_.record_cloud_precision > 0 && type == kCloud;
  const int rec = recorder_ && !skip && (opt_.record_only.empty() || topic_selected(topic, opt_.record_only))
                      ? recorder_->add_topic(topic, pack_cloud ? kPackedCloud : type)
                      : 0;
  const long live = live_ ? static_cast<long>(live_->add_channel(topic, "cdr", type, "omgidl",
                                                                   omgidl_schema(idl_text(type) ? idl_text(type) : ""), type == kCloud))
                          : -1;
  auto scene = scene_handler(topic, type);
  if (!rec && live < 0 && !scene) return;
  auto tap = std::make_shared<Tap>(type);
  if (pack_cloud && rec) tap->packed = std::make_unique<SampleSerializer>(kPackedCloud);
  const double precision = opt_.record_cloud_precision;
  out.tap = [this, rec, live, tap, scene, precision](const void* m) {
    const bool to_live = live >= 0 && live_->wanted(static_cast<std::uint32_t>(live));
    if (!rec && !to_live && !scene) return;
    try {
      if (scene) {
        const auto t0 = Clock::now();  // the live view's own time (summary: live.taps_s)
        try {
          scene(m, static_cast<std::uint64_t>(std::max<std::int64_t>(now_ns(), 0)));
        } catch (const std::exception&) {  // the viewer's picture of a sample: never the run's failure
        }
        live_tap_ns_ += (Clock::now() - t0).count();
      }
      if (!rec && !to_live) return;
      std::lock_guard<std::mutex> l(tap->m);
      const std::int64_t now = now_ns();
      if (rec && tap->packed) {
        const auto q = cloud::pack<msgs::PointCloud, msgs::QuantizedPointCloud>(*static_cast<const msgs::PointCloud*>(m), precision);
        const auto p = tap->packed->serialize(&q);
        recorder_->write(rec, now, p.data, p.size);
      }
      const bool shared = rec && !tap->packed;  // serialized for the recording anyway
      if (!shared && !to_live) return;
      const auto t0 = Clock::now();
      const auto b = tap->serializer.serialize(m);
      if (shared) recorder_->write(rec, now, b.data, b.size);
      if (to_live) {
        const auto t1 = Clock::now();
        live_->publish(static_cast<std::uint32_t>(live), static_cast<std::uint64_t>(std::max<std::int64_t>(now, 0)), b.data, b.size);
        live_tap_ns_ += (Clock::now() - (shared ? t1 : t0)).count();
      }
    } catch (const std::exception& e) {
      request_stop(RunResult::failed, e.what());
    }
  };
}

}  // namespace brickyard::fw
