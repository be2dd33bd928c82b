#pragma once
// A track's centre line as files give it: the TUM racetrack-database format
// (`x_m,y_m,w_tr_right_m,w_tr_left_m`, a closed loop) and racing lines (`x_m,y_m`).
// Framework-free: the simulator, the map source, planning and the tools read files through it.
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::track {

struct CenterLine {
  std::string source;
  std::vector<double> x, y, width_right, width_left;
  // A fifth column, when the file has one: the road's bank angle across the centre line, degrees,
  // positive raising the left edge (a mapped track carries its own: docs/mapping.md). Empty: none.
  std::vector<double> bank_deg;
  // What a reader should say about the file (a bridge where the track crosses itself).
  std::vector<std::string> notes;
};

// A problem with a track file; what() starts with "<file>:<line>:".
class TrackFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Four fields a row, or five with the bank angle (every row alike).
CenterLine parse_centerline_csv(std::istream& in, const std::string& name);
CenterLine load_centerline_csv(const std::string& path);
// Racing lines carry x, y only (TUM `x_m,y_m`); widths are left at zero.
CenterLine load_xy_csv(const std::string& path);

// Writes a track file (with the bank column when bank_deg is filled): to `path`.part, then renamed,
// so a reader never sees half a file. Throws TrackFileError naming the path when it cannot.
void write_centerline_csv(const std::string& path, const CenterLine& line);

// Whether the closed line runs counter-clockwise (positive shoelace area): its outside is then on
// the right.
bool counter_clockwise(const CenterLine& line);

}  // namespace brickyard::track
