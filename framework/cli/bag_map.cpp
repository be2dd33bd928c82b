#include "cli/bag_map.hpp"

#include "graph/diagnostics.hpp"
#include "io/bounded_read.hpp"

#include <nlohmann/json.hpp>

#include <cmath>
#include <set>

namespace brickyard::fw {

namespace {

using nlohmann::json;

// Reads a file's JSON values, each checked, naming FILE#/pointer when one is wrong.
class MapReader {
 public:
  explicit MapReader(std::string file) : file_(std::move(file)) {}
  [[noreturn]] void fail(const json::json_pointer& at, const std::string& why) const { throw InvalidInput(file_ + "#" + at.to_string(), why); }
  const json& object(const json& j, const json::json_pointer& at) const {
    if (!j.is_object()) fail(at, std::string("expected an object, found ") + j.type_name());
    return j;
  }
  double number(const json& j, const json::json_pointer& at, double lo, double hi) const {
    if (!j.is_number() || !std::isfinite(j.get<double>())) fail(at, std::string("expected a number, found ") + j.dump());
    const double v = j.get<double>();
    if (v < lo || v > hi) fail(at, "expected " + json(lo).dump() + " to " + json(hi).dump() + ", found " + j.dump());
    return v;
  }
  void only(const json& j, const json::json_pointer& at, const std::set<std::string>& keys) const {
    for (const auto& [k, v] : j.items())
      if (!keys.count(k)) fail(at / k, "not a key here (keys: " + join(keys) + ")");
  }

 private:
  static std::string join(const std::set<std::string>& keys) {
    std::string s;
    for (const auto& k : keys) s += (s.empty() ? "" : ", ") + k;
    return s;
  }
  std::string file_;
};

MappedTopic mapped_topic(const MapReader& in, const std::string& topic, const json& e, const json::json_pointer& at) {
  in.object(e, at);
  in.only(e, at, {"wire", "sensor_id", "mount", "receiver_id"});
  MappedTopic t;
  t.topic = topic;
  if (!e.contains("wire") || !e["wire"].is_string()) in.fail(at / "wire", "expected the wire it plays onto, \"NODE.PORT\"");
  t.wire = e["wire"].get<std::string>();
  const auto dot = t.wire.find('.');
  if (dot == std::string::npos || dot == 0 || dot + 1 == t.wire.size() || t.wire.find('.', dot + 1) != std::string::npos)
    in.fail(at / "wire", "expected \"NODE.PORT\", found \"" + t.wire + "\"");
  if (e.contains("sensor_id")) t.sensor_id = static_cast<int>(in.number(e["sensor_id"], at / "sensor_id", 0, 255));
  if (e.contains("receiver_id")) t.receiver_id = static_cast<int>(in.number(e["receiver_id"], at / "receiver_id", 0, 255));
  if (e.contains("mount")) {
    const json& m = in.object(e["mount"], at / "mount");
    const char* keys[] = {"x", "y", "z", "roll", "pitch", "yaw"};
    in.only(m, at / "mount", {keys, keys + 6});
    for (int i = 0; i < 6; ++i)
      if (m.contains(keys[i])) t.mount[i] = in.number(m[keys[i]], at / "mount" / keys[i], i < 3 ? -100.0 : -M_PI, i < 3 ? 100.0 : M_PI);
  }
  return t;
}

}  // namespace

BagMap read_bag_map(const std::string& path) {
  BagMap map;
  map.file = path;
  const MapReader in(path);
  std::vector<std::uint8_t> bytes;
  std::string error;
  if (!io::read_regular_file(path, 1 << 20, bytes, error)) throw InvalidInput(path, error);
  json j;
  try {
    j = json::parse(bytes.begin(), bytes.end());
  } catch (const json::parse_error& e) {
    throw InvalidInput(path, std::string("not JSON: ") + e.what());
  }
  const json::json_pointer root;
  in.object(j, root);
  in.only(j, root, {"topics", "datum"});
  if (!j.contains("topics")) in.fail(root / "topics", "missing: the bag's topics to play, each onto its wire");
  std::set<std::string> wires;
  for (const auto& [topic, e] : in.object(j["topics"], root / "topics").items()) {
    map.topics.push_back(mapped_topic(in, topic, e, root / "topics" / topic));
    if (!wires.insert(map.topics.back().wire).second)
      in.fail(root / "topics" / topic / "wire", "\"" + map.topics.back().wire + "\" is another topic's wire already");
  }
  if (map.topics.empty()) in.fail(root / "topics", "no topic to play");
  if (j.contains("datum")) {
    const json& d = in.object(j["datum"], root / "datum");
    in.only(d, root / "datum", {"latitude", "longitude", "altitude"});
    for (const char* k : {"latitude", "longitude", "altitude"})
      if (!d.contains(k)) in.fail(root / "datum" / k, "missing");
    map.datum = std::array<double, 3>{in.number(d["latitude"], root / "datum" / "latitude", -90, 90),
                                      in.number(d["longitude"], root / "datum" / "longitude", -180, 180),
                                      in.number(d["altitude"], root / "datum" / "altitude", -1000, 10000)};
  }
  return map;
}

}  // namespace brickyard::fw
