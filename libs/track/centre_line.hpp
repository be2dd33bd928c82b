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
};

// A problem with a track file; what() starts with "<file>:<line>:".
class TrackFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

CenterLine parse_centerline_csv(std::istream& in, const std::string& name);
CenterLine load_centerline_csv(const std::string& path);
// Racing lines carry x, y only (TUM `x_m,y_m`); widths are left at zero.
CenterLine load_xy_csv(const std::string& path);

// Whether the closed line runs counter-clockwise (positive shoelace area): its outside is then on
// the right.
bool counter_clockwise(const CenterLine& line);

}  // namespace brickyard::track
