#include "centre_line.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>

namespace brickyard::track {
namespace {

std::vector<double> parse_row(const std::string& row, std::size_t want, const std::string& where) {
  std::vector<double> v;
  std::size_t start = 0;
  for (;;) {
    std::size_t comma = row.find(',', start);
    std::string cell = row.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    cell.erase(0, cell.find_first_not_of(" \t\r"));
    cell.erase(cell.find_last_not_of(" \t\r") + 1);
    char* end = nullptr;
    double x = std::strtod(cell.c_str(), &end);
    if (cell.empty() || *end != '\0')
      throw TrackFileError(where + ": field " + std::to_string(v.size() + 1) + " is not a number: '" + cell + "'");
    if (!std::isfinite(x)) throw TrackFileError(where + ": field " + std::to_string(v.size() + 1) + " is not finite");
    v.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() != want)
    throw TrackFileError(where + ": " + std::to_string(v.size()) + " fields, expected " + std::to_string(want));
  return v;
}

CenterLine parse(std::istream& in, const std::string& name, std::size_t fields) {
  CenterLine c;
  c.source = name;
  std::string row;
  int line = 0;
  std::vector<int> lines;
  while (std::getline(in, row)) {
    ++line;
    auto first = row.find_first_not_of(" \t\r");
    if (first == std::string::npos || row[first] == '#') continue;
    const std::string where = name + ":" + std::to_string(line);
    auto v = parse_row(row, fields, where);
    if (fields == 4 && (v[2] <= 0 || v[3] <= 0))
      throw TrackFileError(where + ": track widths must be positive");
    if (!c.x.empty() && std::hypot(v[0] - c.x.back(), v[1] - c.y.back()) < 1e-6)
      throw TrackFileError(where + ": repeats the point of line " + std::to_string(lines.back()));
    c.x.push_back(v[0]);
    c.y.push_back(v[1]);
    c.width_right.push_back(fields == 4 ? v[2] : 0.0);
    c.width_left.push_back(fields == 4 ? v[3] : 0.0);
    lines.push_back(line);
  }
  // A file may close the loop by repeating its first point.
  if (c.x.size() > 1 && std::hypot(c.x.back() - c.x[0], c.y.back() - c.y[0]) < 1e-6) {
    c.x.pop_back(); c.y.pop_back(); c.width_right.pop_back(); c.width_left.pop_back();
  }
  if (c.x.size() < 4) throw TrackFileError(name + ": needs at least 4 points, has " + std::to_string(c.x.size()));
  return c;
}

CenterLine load(const std::string& path, std::size_t fields) {
  std::ifstream f(path);
  if (!f) throw TrackFileError(path + ": cannot open");
  return parse(f, path, fields);
}

}  // namespace

CenterLine parse_centerline_csv(std::istream& in, const std::string& name) { return parse(in, name, 4); }
CenterLine load_centerline_csv(const std::string& path) { return load(path, 4); }
CenterLine load_xy_csv(const std::string& path) { return load(path, 2); }

bool counter_clockwise(const CenterLine& c) {
  const std::size_t n = c.x.size();
  double area = 0;
  for (std::size_t i = 0; i < n; ++i) area += c.x[i] * c.y[(i + 1) % n] - c.x[(i + 1) % n] * c.y[i];
  return area > 0;
}

}  // namespace brickyard::track
