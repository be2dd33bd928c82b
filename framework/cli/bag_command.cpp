// `brickyard bag info RECORDING`: what a recording holds, without decoding a sample; `brickyard
// bag play RECORDING`: its topics republished over DDS (cli/bag_play.hpp).
#include "cli/bag_play.hpp"
#include "cli/command_table.hpp"
#include "record/recording_info.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>

namespace brickyard::fw::cli {
namespace {

namespace fs = std::filesystem;

int bag_play_command(const Args& a) {
  if (a.more.size() != 1) usage_error("bag play", "needs one recording (brickyard bag play RECORDING)");
  BagPlayOptions o;
  o.file = a.more[0];
  o.domain = a.domain.value_or(0);
  o.rate = a.rate;
  o.only = a.only;
  o.security = a.security;
  o.identity = a.identity;
  o.ros2_naming = a.ros2_naming;
  o.map = a.bag_map;
  return bag_play(o);
}

double rate_hz(const TopicStats& t) {
  return t.count > 1 && t.last_ns > t.first_ns ? static_cast<double>(t.count - 1) / (static_cast<double>(t.last_ns - t.first_ns) * 1e-9)
                                               : 0.0;
}

// `bytes`: the file's size, 0 when unknown.
void print_bag_json(const std::string& file, std::uintmax_t bytes, const RecordingInfo& info, const std::vector<TopicStats>& topics,
                    std::int64_t first) {
  nlohmann::json j = {{"file", file}, {"bytes", bytes}, {"clock", info.clock}, {"messages", info.messages},
                      {"start_s", static_cast<double>(first) * 1e-9}, {"end_s", static_cast<double>(info.last_ns) * 1e-9}};
  j["topics"] = nlohmann::json::array();
  for (const auto& t : topics)
    j["topics"].push_back({{"name", t.name}, {"type", t.type}, {"count", t.count}, {"bytes", t.bytes},
                           {"first_s", static_cast<double>(t.first_ns) * 1e-9}, {"last_s", static_cast<double>(t.last_ns) * 1e-9},
                           {"rate_hz", rate_hz(t)}});
  if (!info.damage.empty()) j["damage"] = info.damage;
  std::cout << j.dump(2) << "\n";
}

// `mb`: the file's size in MB, 0 when unknown.
void print_bag_text(const std::string& file, double mb, const RecordingInfo& info, const std::vector<TopicStats>& topics,
                    std::int64_t first) {
  std::printf("file      %s (%.1f MB)\nclock     %s\nspan      %.3f s to %.3f s (%.3f s)\nmessages  %llu\n", file.c_str(), mb,
              info.clock.c_str(), static_cast<double>(first) * 1e-9, static_cast<double>(info.last_ns) * 1e-9,
              static_cast<double>(info.last_ns - first) * 1e-9, static_cast<unsigned long long>(info.messages));
  std::size_t wn = 5, wt = 4;
  for (const auto& t : topics) wn = std::max(wn, t.name.size()), wt = std::max(wt, t.type.size());
  std::printf("\n%-*s  %-*s  %10s  %9s  %12s\n", static_cast<int>(wn), "topic", static_cast<int>(wt), "type", "count", "rate Hz", "MB");
  for (const auto& t : topics)
    std::printf("%-*s  %-*s  %10llu  %9.2f  %12.3f\n", static_cast<int>(wn), t.name.c_str(), static_cast<int>(wt), t.type.c_str(),
                static_cast<unsigned long long>(t.count), rate_hz(t), static_cast<double>(t.bytes) / 1e6);
}

int bag_info(const Args& a) {
  if (a.more.size() != 1) usage_error("bag info", "needs one recording (brickyard run GRAPH --record FILE)");
  const std::string& file = a.more[0];
  RecordingInfo info;
  std::vector<TopicStats> topics;
  try {
    if (is_mcap_file(file)) {
      read_mcap_recording(file, info, topics);
    } else {
      info = read_recording_info(file);
      topics = read_topic_stats(file);
    }
  } catch (const std::exception& e) {
    usage_error(file, e.what());
  }
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  std::int64_t first = 0;
  bool any = false;
  for (const auto& t : topics)
    if (t.count) first = any ? std::min(first, t.first_ns) : t.first_ns, any = true;
  if (a.json) print_bag_json(file, ec ? 0 : size, info, topics, first);
  else print_bag_text(file, ec ? 0.0 : static_cast<double>(size) / 1e6, info, topics, first);
  // A damaged file is read up to the damage (above), then refused: what it lacks is unknown.
  if (!info.damage.empty()) {
    std::fprintf(stderr, "error: %s: %s (what is above was read before it)\n", file.c_str(), info.damage.c_str());
    return 2;
  }
  return 0;
}

}  // namespace

int cmd_bag(const Args& a) {
  if (a.target == "play") return bag_play_command(a);
  if (a.target != "info")
    usage_error(a.target.empty() ? "bag" : "bag " + a.target, a.target.empty() ? "needs a command (brickyard bag info | play RECORDING)"
                                                                             : "unknown bag command (brickyard bag info | play RECORDING)");
  return bag_info(a);
}

}  // namespace brickyard::fw::cli
