#include "centre_line.hpp"

#include "band_overlap.hpp"
#include "io/bounded_read.hpp"
#include "io/whole_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace brickyard::track {
namespace {

std::vector<double> parse_row(const std::string& row, std::size_t want, std::size_t or_want, const std::string& where) {
  std::vector<double> v;
  std::size_t start = 0;
  for (;;) {
    std::size_t comma = row.find(',', start);
    std::string cell = row.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    cell.erase(0, cell.find_first_not_of(" \t\r"));
    cell.erase(cell.find_last_not_of(" \t\r") + 1);
    // Decimal only (strtod also reads hexadecimal floats, 0x1p3, which no track file holds).
    double x = 0;
    const auto [end, err] = std::from_chars(cell.data(), cell.data() + cell.size(), x, std::chars_format::general);
    if (cell.empty() || err != std::errc() || end != cell.data() + cell.size())
      throw TrackFileError(where + ": field " + std::to_string(v.size() + 1) + " is not a number: '" + cell + "'");
    if (!std::isfinite(x)) throw TrackFileError(where + ": field " + std::to_string(v.size() + 1) + " is not finite");
    v.push_back(x);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (v.size() != want && v.size() != or_want)
    throw TrackFileError(where + ": " + std::to_string(v.size()) + " fields, expected " + std::to_string(want) +
                         (or_want != want ? " (or " + std::to_string(or_want) + " with the bank angle, as the first row)" : ""));
  return v;
}

// What a file of a real track can hold (a point at x = 1e308 was read as a track "of
// length inf", and the road graph on it allocated until bad_alloc). Bounds far beyond any circuit.
constexpr double kMaxCoordinate_m = 1e6;  // 1000 km from the file's origin
constexpr double kMaxWidth_m = 100;       // from the centre line to an edge
constexpr double kMaxStep_m = 200;        // between two points of the file (and, for a track, round from the last to the first)
constexpr std::size_t kMaxPoints = 1'000'000;

// Checks one row's values (read at `where`) against the bounds and the point before it (read at
// line lines.back()), then appends the point to c.
void add_point(CenterLine& c, const std::vector<double>& v, std::size_t fields, const std::vector<int>& lines, const std::string& where) {
  if (v.size() == 5) {
    if (std::abs(v[4]) > 45) throw TrackFileError(where + ": bank angle " + std::to_string(v[4]) + " deg is beyond 45");
    c.bank_deg.push_back(v[4]);
  }
  if (fields == 4 && (v[2] <= 0 || v[3] <= 0))
    throw TrackFileError(where + ": track widths must be positive");
  if (fields == 4 && (v[2] > kMaxWidth_m || v[3] > kMaxWidth_m))
    throw TrackFileError(where + ": a track width over " + std::to_string(static_cast<int>(kMaxWidth_m)) + " m");
  if (std::abs(v[0]) > kMaxCoordinate_m || std::abs(v[1]) > kMaxCoordinate_m)
    throw TrackFileError(where + ": a point more than 1000 km from the origin");
  if (!c.x.empty() && std::hypot(v[0] - c.x.back(), v[1] - c.y.back()) > kMaxStep_m)
    throw TrackFileError(where + ": " + std::to_string(static_cast<int>(std::hypot(v[0] - c.x.back(), v[1] - c.y.back()))) +
                         " m from the point of line " + std::to_string(lines.back()) + " (points at most " +
                         std::to_string(static_cast<int>(kMaxStep_m)) + " m apart)");
  if (c.x.size() >= kMaxPoints) throw TrackFileError(where + ": more than " + std::to_string(kMaxPoints) + " points");
  if (!c.x.empty() && std::hypot(v[0] - c.x.back(), v[1] - c.y.back()) < 1e-6)
    throw TrackFileError(where + ": repeats the point of line " + std::to_string(lines.back()));
  c.x.push_back(v[0]);
  c.y.push_back(v[1]);
  c.width_right.push_back(fields == 4 ? v[2] : 0.0);
  c.width_left.push_back(fields == 4 ? v[3] : 0.0);
}

// A file may close the loop by repeating its first point: that repeat is dropped.
void drop_closing_repeat(CenterLine& c) {
  if (c.x.size() > 1 && std::hypot(c.x.back() - c.x[0], c.y.back() - c.y[0]) < 1e-6) {
    c.x.pop_back(); c.y.pop_back(); c.width_right.pop_back(); c.width_left.pop_back();
    if (!c.bank_deg.empty()) c.bank_deg.pop_back();
  }
}

// A track is a loop: its last point leads back to its first. `lines` are the points' file lines.
void check_closed_loop(const CenterLine& c, const std::string& name, const std::vector<int>& lines) {
  if (std::hypot(c.x.back() - c.x[0], c.y.back() - c.y[0]) > kMaxStep_m)
    throw TrackFileError(name + ": not a closed loop: its last point (line " + std::to_string(lines.back()) + ") is " +
                         std::to_string(static_cast<int>(std::hypot(c.x.back() - c.x[0], c.y.back() - c.y[0]))) +
                         " m from its first (at most " + std::to_string(static_cast<int>(kMaxStep_m)) + " m)");
  // Nor one whose ends are far apart for its spacing (a C, an open stretch): every track of the
  // TUM database closes with a gap of its usual spacing (5 m); 4 times it, and at least 20 m.
  std::vector<double> steps;
  for (std::size_t i = 0; i + 1 < c.x.size(); ++i) steps.push_back(std::hypot(c.x[i + 1] - c.x[i], c.y[i + 1] - c.y[i]));
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  const double usual = steps[steps.size() / 2], gap = std::hypot(c.x.back() - c.x[0], c.y.back() - c.y[0]);
  if (gap > std::max(4 * usual, 20.0)) {
    char what[200];
    std::snprintf(what, sizeof what, "not a closed loop: its last point (line %d) is %.1f m from its first, more than 4 times "
                  "its points' usual spacing (%.1f m)", lines.back(), gap, usual);
    throw TrackFileError(name + ": " + what);
  }
}

// A track's band does not run over itself; a bridge (a steep crossing) is read, and said in c.notes.
void check_band_of(CenterLine& c, const std::string& name, const std::vector<int>& lines) {
  const BandCheck band = check_band(c);
  if (const auto& o = band.overlap) {
    char what[200];
    if (o->distance_m == 0)
      std::snprintf(what, sizeof what,
                    "its centre line crosses itself between lines %d and %d at %.0f degrees: two stretches over each "
                    "other, not a bridge (one of at least %.0f degrees)",
                    lines[o->a], lines[o->b], o->angle_deg, kBridgeMinAngleDeg);
    else
      std::snprintf(what, sizeof what,
                    "the track runs over itself: near lines %d and %d two stretches are %.2f m apart centre to "
                    "centre, less than their facing widths together (%.2f m)", lines[o->a], lines[o->b], o->distance_m, o->widths_m);
    throw TrackFileError(name + ": " + what);
  }
  for (const auto& b : band.bridges) {
    char what[160];
    std::snprintf(what, sizeof what, "the track crosses itself between lines %d and %d at %.0f degrees: a bridge", lines[b.a],
                  lines[b.b], b.angle_deg);
    c.notes.push_back(name + ": " + what);
  }
}

CenterLine parse(std::istream& in, const std::string& name, std::size_t fields) {
  CenterLine c;
  c.source = name;
  std::string row;
  int line = 0;
  std::vector<int> lines;  // each point's line in the file
  while (std::getline(in, row)) {
    ++line;
    auto first = row.find_first_not_of(" \t\r");
    if (first == std::string::npos || row[first] == '#') continue;
    const std::string where = name + ":" + std::to_string(line);
    // A track file's first row says whether it carries the bank column; every row then does.
    const std::size_t want = fields == 4 && !lines.empty() ? (c.bank_deg.empty() ? 4 : 5) : fields;
    auto v = parse_row(row, want, fields == 4 && lines.empty() ? 5 : want, where);
    add_point(c, v, fields, lines, where);
    lines.push_back(line);
  }
  drop_closing_repeat(c);
  if (c.x.size() < 4) throw TrackFileError(name + ": needs at least 4 points, has " + std::to_string(c.x.size()));
  if (fields == 4) {
    check_closed_loop(c, name, lines);
    check_band_of(c, name, lines);
  }
  return c;
}

// A track of 100,000 points is some 4 MB: 64 MiB is far past any, and a FIFO or /dev/zero is
// refused before a byte is read (read whole, one would hang or grow without end).
constexpr std::size_t kMaxTrackBytes = std::size_t{64} << 20;

CenterLine load(const std::string& path, std::size_t fields) {
  std::vector<std::uint8_t> bytes;
  std::string error;
  if (!io::read_regular_file(path, kMaxTrackBytes, bytes, error)) throw TrackFileError(error);
  std::istringstream f(std::string(bytes.begin(), bytes.end()));
  return parse(f, path, fields);
}

}  // namespace

CenterLine parse_centerline_csv(std::istream& in, const std::string& name) { return parse(in, name, 4); }
CenterLine load_centerline_csv(const std::string& path) { return load(path, 4); }
CenterLine load_xy_csv(const std::string& path) { return load(path, 2); }

void write_centerline_csv(const std::string& path, const CenterLine& c) {
  const bool bank = !c.bank_deg.empty();
  if (bank && c.bank_deg.size() != c.x.size()) throw TrackFileError(path + ": one bank angle per point needed");
  std::ostringstream f;
  f << "# x_m,y_m,w_tr_right_m,w_tr_left_m" << (bank ? ",bank_deg" : "") << "\n";
  char row[192];
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    const int n = bank ? std::snprintf(row, sizeof row, "%.4f,%.4f,%.4f,%.4f,%.3f\n", c.x[i], c.y[i], c.width_right[i],
                                       c.width_left[i], c.bank_deg[i])
                       : std::snprintf(row, sizeof row, "%.4f,%.4f,%.4f,%.4f\n", c.x[i], c.y[i], c.width_right[i], c.width_left[i]);
    f.write(row, n);
  }
  try {
    io::write_whole_file(path, f.str());
  } catch (const io::WriteError& e) {
    throw TrackFileError(e.what());
  }
}

bool counter_clockwise(const CenterLine& c) {
  const std::size_t n = c.x.size();
  double area = 0;
  for (std::size_t i = 0; i < n; ++i) area += c.x[i] * c.y[(i + 1) % n] - c.x[(i + 1) % n] * c.y[i];
  return area > 0;
}

}  // namespace brickyard::track
