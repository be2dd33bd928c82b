#include "ouster_metadata.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

namespace brickyard::drivers {

namespace {

using nlohmann::json;

// Reads fields by dotted path ("lidar_data_format.columns_per_frame") without exceptions: the first
// failure is kept in `error`, naming the path, and later reads are no-ops that return defaults.
class FieldReader {
 public:
  explicit FieldReader(const json& root) : root_(root) {}

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  void fail(const std::string& path, const std::string& why) {
    if (ok()) error_ = path + ": " + why;
  }

  const json* find(std::string_view path) const {
    const json* node = &root_;
    while (!path.empty()) {
      size_t dot = path.find('.');
      std::string key(path.substr(0, dot));
      if (!node->is_object()) return nullptr;
      auto it = node->find(key);
      if (it == node->end()) return nullptr;
      node = &*it;
      path = dot == std::string_view::npos ? std::string_view{} : path.substr(dot + 1);
    }
    return node;
  }

  std::optional<double> number(const std::string& path, bool required) {
    const json* node = find(path);
    if (node == nullptr) {
      if (required) fail(path, "missing");
      return std::nullopt;
    }
    if (!node->is_number()) {
      fail(path, "expected a number, got " + std::string(node->type_name()));
      return std::nullopt;
    }
    return node->get<double>();
  }

  // An integer in [lo, hi]; `fallback` when absent and not required.
  int64_t integer(const std::string& path, int64_t lo, int64_t hi, bool required, int64_t fallback) {
    auto value = number(path, required);
    if (!value) return fallback;
    if (*value != std::floor(*value) || *value < static_cast<double>(lo) || *value > static_cast<double>(hi)) {
      fail(path, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
      return fallback;
    }
    return static_cast<int64_t>(*value);
  }

  std::optional<std::string> text(const std::string& path, bool required) {
    const json* node = find(path);
    if (node == nullptr) {
      if (required) fail(path, "missing");
      return std::nullopt;
    }
    if (!node->is_string()) {
      fail(path, "expected a string, got " + std::string(node->type_name()));
      return std::nullopt;
    }
    return node->get<std::string>();
  }

  // Exactly `count` finite numbers.
  std::vector<double> numbers(const std::string& path, size_t count, const std::string& count_name) {
    const json* node = find(path);
    if (node == nullptr) {
      fail(path, "missing");
      return {};
    }
    if (!node->is_array() || node->size() != count) {
      fail(path, "expected " + std::to_string(count) + " numbers (" + count_name + "), got " +
                     (node->is_array() ? std::to_string(node->size()) : std::string(node->type_name())));
      return {};
    }
    std::vector<double> out;
    out.reserve(count);
    for (const json& v : *node) {
      if (!v.is_number() || !std::isfinite(v.get<double>())) {
        fail(path, "expected only finite numbers");
        return {};
      }
      out.push_back(v.get<double>());
    }
    return out;
  }

 private:
  const json& root_;
  std::string error_;
};

// Where each field lives: the nested layout of later SDKs, or the flat one of firmware 2.x.
struct Paths {
  std::string format, beams, lidar_intrinsics, sensor, config, imu_intrinsics;
  static Paths for_root(const json& root) {
    if (root.contains("beam_intrinsics")) {
      return {"lidar_data_format.", "beam_intrinsics.", "lidar_intrinsics.", "sensor_info.", "config_params.", "imu_intrinsics."};
    }
    return {"data_format.", "", "", "", "", ""};
  }
};

bool profile_from_name(const std::string& name, OusterProfile& out) {
  if (name == "LEGACY") out = OusterProfile::legacy;
  else if (name == "RNG19_RFL8_SIG16_NIR16") out = OusterProfile::single_return;
  else if (name == "RNG15_RFL8_NIR8") out = OusterProfile::low_data_rate;
  else if (name == "RNG19_RFL8_SIG16_NIR16_DUAL") out = OusterProfile::dual_return;
  else return false;
  return true;
}

void read_data_format(FieldReader& r, const Paths& p, OusterMetadata& m) {
  m.columns_per_packet = static_cast<int>(r.integer(p.format + "columns_per_packet", 1, 256, true, 16));
  m.columns_per_frame = static_cast<int>(r.integer(p.format + "columns_per_frame", 1, 16384, true, 1024));
  m.pixels_per_column = static_cast<int>(r.integer(p.format + "pixels_per_column", 1, 512, true, 0));
  if (!r.ok()) return;
  if (m.columns_per_frame % m.columns_per_packet != 0) {
    r.fail(p.format + "columns_per_frame", "not a multiple of columns_per_packet");
    return;
  }
  const std::string rows = "pixels_per_column";
  std::vector<double> shift = r.numbers(p.format + "pixel_shift_by_row", m.pixels_per_column, rows);
  m.pixel_shift_by_row.assign(shift.begin(), shift.end());
  std::vector<double> window = r.numbers(p.format + "column_window", 2, "first and last column");
  for (double c : window) {
    if (c != std::floor(c) || c < 0 || c >= m.columns_per_frame) {
      r.fail(p.format + "column_window", "expected two columns in [0, columns_per_frame)");
    }
  }
  if (!r.ok()) return;
  m.column_window_first = static_cast<int>(window[0]);
  m.column_window_last = static_cast<int>(window[1]);
}

void read_profile(FieldReader& r, const Paths& p, OusterMetadata& m) {
  auto name = r.text(p.format + "udp_profile_lidar", false);
  std::string path = p.format + "udp_profile_lidar";
  if (!name && !p.config.empty()) {
    name = r.text(p.config + "udp_profile_lidar", false);
    path = p.config + "udp_profile_lidar";
  }
  if (!name) return;  // firmware before 2.2 names no profile: LEGACY
  if (!profile_from_name(*name, m.profile)) {
    r.fail(path, "unknown profile '" + *name +
                     "' (known: LEGACY, RNG19_RFL8_SIG16_NIR16, RNG15_RFL8_NIR8, RNG19_RFL8_SIG16_NIR16_DUAL)");
  }
}

// lidar_mode is "<columns>x<frames per second>"; its columns must agree with the data format's.
void read_lidar_mode(FieldReader& r, const Paths& p, OusterMetadata& m) {
  std::string path = p.config + "lidar_mode";
  auto mode = r.text(path, false);
  if (!mode) {  // some saved files keep only the rate
    m.frames_per_second = static_cast<int>(r.integer(p.format + "fps", 1, 100, false, 0));
    if (m.frames_per_second == 0) r.fail(path, "missing (and no " + p.format + "fps)");
    return;
  }
  m.lidar_mode = *mode;
  int columns = 0;
  int fps = 0;
  const char* end = mode->data() + mode->size();
  auto [x, ec1] = std::from_chars(mode->data(), end, columns);
  if (ec1 != std::errc{} || x == end || *x != 'x' || std::from_chars(x + 1, end, fps).ptr != end || fps <= 0) {
    r.fail(path, "expected <columns>x<rate>, got '" + *mode + "'");
    return;
  }
  if (columns != m.columns_per_frame) {
    r.fail(path, "'" + *mode + "' disagrees with columns_per_frame " + std::to_string(m.columns_per_frame));
    return;
  }
  m.frames_per_second = fps;
}

std::array<double, 16> transform(FieldReader& r, const std::string& path) {
  std::array<double, 16> out{};
  std::vector<double> v = r.numbers(path, 16, "a row-major 4x4 matrix");
  if (v.size() == 16) std::copy(v.begin(), v.end(), out.begin());
  return out;
}

void read_beams(FieldReader& r, const Paths& p, OusterMetadata& m) {
  const std::string rows = "pixels_per_column";
  m.beam_altitude_deg = r.numbers(p.beams + "beam_altitude_angles", m.pixels_per_column, rows);
  m.beam_azimuth_deg = r.numbers(p.beams + "beam_azimuth_angles", m.pixels_per_column, rows);
  m.lidar_origin_to_beam_origin_mm = r.number(p.beams + "lidar_origin_to_beam_origin_mm", true).value_or(0.0);
  if (r.find(p.beams + "beam_to_lidar_transform") != nullptr) {
    m.beam_to_lidar = transform(r, p.beams + "beam_to_lidar_transform");
  } else {
    m.beam_to_lidar = {1, 0, 0, m.lidar_origin_to_beam_origin_mm, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  }
  m.lidar_to_sensor = transform(r, p.lidar_intrinsics + "lidar_to_sensor_transform");
  // The IMU's: the identity when the file has none (a capture's IMU packets then read in its own axes).
  if (r.find(p.imu_intrinsics + "imu_to_sensor_transform") != nullptr)
    m.imu_to_sensor = transform(r, p.imu_intrinsics + "imu_to_sensor_transform");
}

// "ousteros-image-prod-aries-v2.3.0+2022..." or "v2.1.1": the first "v<major>.<minor>".
bool firmware_version(const std::string& text, int& major, int& minor) {
  for (size_t i = text.find('v'); i != std::string::npos; i = text.find('v', i + 1)) {
    const char* end = text.data() + text.size();
    auto [dot, ec] = std::from_chars(text.data() + i + 1, end, major);
    if (ec == std::errc{} && dot != end && *dot == '.' && std::from_chars(dot + 1, end, minor).ec == std::errc{}) {
      return true;
    }
  }
  return false;
}

// prod_sn: a string of digits in the files seen, a number in some; empty or absent reads as 0.
void read_serial(FieldReader& r, const std::string& path, uint64_t& serial) {
  const json* sn = r.find(path);
  if (sn == nullptr) return;
  if (sn->is_number_unsigned()) {
    serial = sn->get<uint64_t>();
    return;
  }
  const std::string* digits = sn->get_ptr<const std::string*>();
  if (digits != nullptr && digits->empty()) return;
  if (digits == nullptr ||
      std::from_chars(digits->data(), digits->data() + digits->size(), serial).ptr != digits->data() + digits->size()) {
    r.fail(path, "expected a serial number of digits");
  }
}

void read_identity(FieldReader& r, const Paths& p, OusterMetadata& m) {
  read_serial(r, p.sensor + "prod_sn", m.serial_number);
  m.initialization_id = static_cast<uint32_t>(r.integer(p.sensor + "initialization_id", 0, 0xFFFFFF, false, 0));
  m.product_line = r.text(p.sensor + "prod_line", false).value_or("");
  for (const char* key : {"image_rev", "build_rev"}) {
    auto rev = r.text(p.sensor + key, false);
    if (rev && firmware_version(*rev, m.firmware_major, m.firmware_minor)) break;
  }
  m.packet_crc = m.firmware_major > 3 || (m.firmware_major == 3 && m.firmware_minor >= 1);
  m.udp_port_lidar = static_cast<int>(r.integer(p.config + "udp_port_lidar", 0, 65535, false, 7502));
  m.udp_port_imu = static_cast<int>(r.integer(p.config + "udp_port_imu", 0, 65535, false, 7503));
}

}  // namespace

const char* to_string(OusterProfile profile) {
  switch (profile) {
    case OusterProfile::legacy: return "LEGACY";
    case OusterProfile::single_return: return "RNG19_RFL8_SIG16_NIR16";
    case OusterProfile::low_data_rate: return "RNG15_RFL8_NIR8";
    case OusterProfile::dual_return: return "RNG19_RFL8_SIG16_NIR16_DUAL";
  }
  return "unknown";
}

bool parse_ouster_metadata(std::string_view json_text, OusterMetadata& out, std::string& error) {
  json root = json::parse(json_text.begin(), json_text.end(), nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded() || !root.is_object()) {
    error = "metadata: not a JSON object";
    return false;
  }
  Paths paths = Paths::for_root(root);
  FieldReader reader(root);
  OusterMetadata m;
  read_data_format(reader, paths, m);
  if (reader.ok()) read_profile(reader, paths, m);
  if (reader.ok()) read_lidar_mode(reader, paths, m);
  if (reader.ok()) read_beams(reader, paths, m);
  if (reader.ok()) read_identity(reader, paths, m);
  if (!reader.ok()) {
    error = reader.error();
    return false;
  }
  out = std::move(m);
  error.clear();
  return true;
}

}  // namespace brickyard::drivers
