#include "cli/bag_play.hpp"

#include "cli/bag_players.hpp"

#include "exec/executive.hpp"  // g_interrupt
#include "cdr/cdr_json.hpp"
#include "cdr/cdr_reader.hpp"
#include "record/recorder.hpp"
#include "record/recording_info.hpp"
#include "graph/diagnostics.hpp"
#include "security/security_files.hpp"
#include "transport/dds.hpp"
#include "transport/wire_types.hpp"

#include "cloud/quantized_cloud.hpp"

#include <brickyard/msgs/PointCloud.h>
#include <brickyard/msgs/QuantizedPointCloud.h>

#include <brickyard/msgs/registry.hpp>

#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/rtps/common/SerializedPayload.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <thread>

namespace brickyard::fw {

namespace {
void on_signal(int) { g_interrupt = true; }

// Where a sample stops fitting its type: the IDL decoder, which counts bytes, says.
std::string where_it_breaks(const std::string& type, const unsigned char* data, std::size_t size) {
  const char* idl = idl_text(type);
  if (!idl) return {};
  try {
    cdr::CdrJson(omgidl_schema(idl)).decode(type, data, size);
  } catch (const std::exception& e) {
    return std::string(": ") + e.what();
  }
  return {};
}

// The recording's summary, `info`: 0, or 2 (said on stderr) when it cannot be read, is damaged or
// holds no sample.
int read_recording(const BagPlayOptions& o, RecordingInfo& info) {
  try {
    info = read_recording_info(o.file);
  } catch (const std::exception& e) {
    const bool foreign = std::strstr(e.what(), "not a brickyard recording") != nullptr;
    std::fprintf(stderr, "error: %s: %s%s\n", o.file.c_str(), e.what(), foreign ? " (a ROS 2 bag of your own plays with --map FILE: docs/ros2.md)" : "");
    return 2;
  }
  // A damaged file is refused: what it lacks is unknown (bag info reads up to the damage).
  if (!info.damage.empty()) return std::fprintf(stderr, "error: %s: %s\n", o.file.c_str(), info.damage.c_str()), 2;
  if (info.messages == 0) return std::fprintf(stderr, "error: %s: the recording holds no samples\n", o.file.c_str()), 2;
  return 0;
}

// --identity P: the player stands in for process P of a split graph (its participant named as
// P's is, so that P's readers' peers take it for P where security is off; secured, P's
// certificate decides).
DdsSettings player_settings(const BagPlayOptions& o) {
  DdsSettings ds;
  ds.domain = o.domain;
  if (!o.identity.empty()) ds.name = participant_name(o.identity);
  ds.ros2_naming = o.ros2_naming;
  if (!o.security.empty()) {
    if (o.identity.empty()) throw InvalidInput("--security " + o.security, "bag play writes topics: it needs --identity NAME, a process of the graph allowed to write them");
    ds.security = security::security_identity(o.security, o.identity);
  }
  return ds;
}

// A writer for each recorded topic --only selects: 0, or 2 (said on stderr) for a type this build
// does not know.
int make_players(const BagPlayOptions& o, const RecordingInfo& info, DdsTransport& dds, Players& topics) {
  for (const auto& [name, type] : info.topics) {
    if (!o.only.empty() && !topic_selected(name, o.only)) continue;
    if (type.rfind("foxglove.", 0) == 0) continue;  // the scene (/tf, /scene/*): drawn from the wires, no wire of its own
    const auto* entry = find_wire_type(type);
    const auto dot = name.find('.');
    if (!entry || dot == std::string::npos) {
      std::fprintf(stderr, "error: %s: topic %s holds %s, which this build does not know\n", o.file.c_str(), name.c_str(), type.c_str());
      return 2;
    }
    auto p = std::make_unique<Played>();
    p->support.reset(entry->make());
    p->sample = p->support->createData();
    p->packed = type == message_traits<msgs::QuantizedPointCloud>::name;
    p->writer = dds.make_writer(topic_name(name.substr(0, dot), name.substr(dot + 1)), p->packed ? message_traits<msgs::PointCloud>::name : type);
    topics[name] = std::move(p);
  }
  return 0;
}

// One sample of `topic`, decoded into its message and written: empty, or why it could not be.
std::string play_sample(Played& p, const std::string& topic, const unsigned char* data, std::size_t size) {
  if (p.convert) {
    const std::string which = "sample " + std::to_string(p.count + p.damaged) + " of " + topic + ": ";
    try {
      p.convert(data, size);
    } catch (const cdr::DamagedSample& e) {  // one message lost: counted and skipped, the first named
      if (p.damaged++ == 0) p.first_damage = which + e.what();
      return {};
    } catch (const std::invalid_argument& e) {
      return which + e.what();
    }
    return {};
  }
  if (p.payload.max_size < size) p.payload.reserve(static_cast<std::uint32_t>(size));
  std::memcpy(p.payload.data, data, size);
  p.payload.length = static_cast<std::uint32_t>(size);
  p.payload.pos = 0;
  if (!p.support->deserialize(&p.payload, p.sample))
    return "sample " + std::to_string(p.count) + " of " + topic + " does not decode as " + p.support->getName() +
           where_it_breaks(p.support->getName(), data, size);
  if (p.packed) {
    try {
      p.cloud = cloud::unpack<msgs::PointCloud>(*static_cast<const msgs::QuantizedPointCloud*>(p.sample));
    } catch (const std::invalid_argument& e) {
      return "sample " + std::to_string(p.count) + " of " + topic + ": " + e.what();
    }
    p.writer->write(&p.cloud);
  } else {
    p.writer->write(p.sample);
  }
  return {};
}

}  // namespace

// Every sample of the played topics at its recorded time from `start` (`rate` times as fast),
// until the end or Ctrl-C: empty, or what went wrong. `played` counts them.
std::string play_samples(const BagPlayOptions& o, Players& topics, Clock::time_point start, std::uint64_t& played) {
  std::int64_t first = -1;
  std::string error;
  try {
    for_each_sample(o.file, [&](const std::string& topic, const std::string&, std::int64_t stamp, const unsigned char* data, std::size_t size) {
      if (g_interrupt || !error.empty()) return;
      auto it = topics.find(topic);
      if (it == topics.end()) return;
      Played& p = *it->second;
      if (first < 0) first = stamp;
      const auto due = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(static_cast<double>(stamp - first) * 1e-9 / o.rate));
      while (!g_interrupt && Clock::now() < due) std::this_thread::sleep_until(std::min(due, Clock::now() + std::chrono::milliseconds(50)));
      const std::uint64_t damaged = p.damaged;
      error = play_sample(p, topic, data, size);
      if (!error.empty() || p.damaged != damaged) return;  // (a damaged sample skipped: not played)
      ++p.count;
      ++played;
    });
  } catch (const std::exception& e) {
    error = e.what();
  }
  return error;
}

int bag_play(const BagPlayOptions& o) {
  RecordingInfo info;
  if (o.map.empty())
    if (const int rc = read_recording(o, info)) return rc;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  DdsTransport dds(player_settings(o));
  Players topics;
  if (const int rc = o.map.empty() ? make_players(o, info, dds, topics) : make_mapped_players(o, dds, topics)) return rc;
  if (topics.empty()) return std::fprintf(stderr, "error: %s: no recorded topic matches --only\n", o.file.c_str()), 2;
  // Readers elsewhere need a moment to match the new writers before the first sample.
  std::this_thread::sleep_for(std::chrono::duration<double>(o.preroll_s));
  const auto start = Clock::now();
  std::uint64_t played = 0;
  const std::string error = play_samples(o, topics, start, played);
  if (!error.empty()) return std::fprintf(stderr, "error: %s: %s\n", o.file.c_str(), error.c_str()), 2;
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  for (const auto& [name, p] : topics)
    if (p->damaged) std::fprintf(stderr, "bag play: %llu damaged samples of %s skipped (the first: %s)\n", static_cast<unsigned long long>(p->damaged),
                                 name.c_str(), p->first_damage.c_str());
  std::fprintf(stderr, "bag play: %llu samples of %zu topics in %.2f s%s\n", static_cast<unsigned long long>(played), topics.size(), wall,
               g_interrupt ? " (interrupted)" : "");
  return g_interrupt ? 1 : 0;
}

}  // namespace brickyard::fw
