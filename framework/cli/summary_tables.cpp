#include "cli/summary_tables.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

namespace brickyard::fw::cli {

std::string summary_table(const nlohmann::json& j) {
  if (!j.contains("nodes") || j["nodes"].empty()) return "";
  std::size_t wn = 4, wp = 6;
  for (const auto& [name, n] : j["nodes"].items()) {
    wn = std::max(wn, name.size());
    wp = std::max(wp, n.value("plugin", std::string()).size());
  }
  auto num = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.4g", v);
    return std::string(b);
  };
  auto value = [&](const nlohmann::json& v) -> std::string {
    if (v.is_number()) return num(v.get<double>());
    if (v.is_string()) return v.get<std::string>();
    if (v.is_array()) {
      std::string out = "[";
      for (std::size_t i = 0; i < v.size() && i < 4; ++i) out += (i ? " " : "") + (v[i].is_number() ? num(v[i].get<double>()) : v[i].dump());
      return out + (v.size() > 4 ? " … (" + std::to_string(v.size()) + ")]" : "]");
    }
    return v.dump();
  };
  std::string out;
  char row[256];
  std::snprintf(row, sizeof row, "%-*s  %-*s  %8s  %s\n", static_cast<int>(wn), "node", static_cast<int>(wp), "plugin", "steps", "metrics");
  out += row;
  for (const auto& [name, n] : j["nodes"].items()) {
    std::string m;
    if (n.contains("metrics"))
      for (const auto& [k, v] : n["metrics"].items()) m += (m.empty() ? "" : " · ") + k + " " + value(v);
    std::snprintf(row, sizeof row, "%-*s  %-*s  %8llu  ", static_cast<int>(wn), name.c_str(), static_cast<int>(wp),
                  n.value("plugin", std::string()).c_str(), static_cast<unsigned long long>(n.value("steps", 0ull)));
    out += row + (m.empty() ? "—" : m) + "\n";
  }
  return out;
}

std::string profile_table(const nlohmann::json& j) {
  std::vector<std::pair<double, std::string>> rows;
  std::size_t wn = 4;
  double total = 0;
  for (const auto& [name, n] : j["nodes"].items()) {
    const double s = n.value("step_wall_s", 0.0);
    rows.emplace_back(s, name);
    wn = std::max(wn, name.size());
    total += s;
  }
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first > b.first || (a.first == b.first && a.second < b.second); });
  const double wall = j.value("wall_time_s", 0.0);
  std::string out;
  char row[256];
  std::snprintf(row, sizeof row, "%-*s  %10s  %10s  %8s\n", static_cast<int>(wn), "node", "step ms", "us/step", "of wall");
  out += row;
  for (const auto& [s, name] : rows) {
    const auto steps = j["nodes"][name].value("steps", 0ull);
    std::snprintf(row, sizeof row, "%-*s  %10.1f  %10.1f  %7.1f%%\n", static_cast<int>(wn), name.c_str(), s * 1e3,
                  steps ? s * 1e6 / static_cast<double>(steps) : 0.0, wall > 0 ? 100 * s / wall : 0.0);
    out += row;
  }
  std::snprintf(row, sizeof row, "%-*s  %10.1f  %10s  %7.1f%%  (the rest: the host, the transport, start and end)\n", static_cast<int>(wn),
                "all nodes", total * 1e3, "", wall > 0 ? 100 * total / wall : 0.0);
  return out + row;
}

}  // namespace brickyard::fw::cli
