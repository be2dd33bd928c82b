#pragma once
// What the report draws, read from a run's recording (docs/recording.md): topics found by their
// message type, decoded into plain series. Framework-free apart from the SDK's message types.
#include <string>
#include <vector>

namespace brickyard::report {

struct Pose {
  double t, x, y, speed, s, d;  // s, d: along and off the centre line (VehicleState)
};
struct Fix {
  double t, x, y;
  int receiver;
};
struct Estimate {
  double t, x, y;
  std::vector<double> delta;  // per receiver
};
struct Mode {
  double t;
  int mode;
  std::string name;
};
struct Steer {
  double t, steer;
};
struct PathSnapshot {
  double t;
  std::vector<double> x, y;
};
struct Pylon {
  double x, y, radius, s, d;
};

struct RunData {
  std::vector<double> left_x, left_y, right_x, right_y;  // track edges (closed)
  std::vector<double> centre_x, centre_y, width_left, width_right;  // the centre line
  std::vector<Pylon> pylons;
  std::vector<Pose> truth;
  std::vector<Fix> fixes;
  std::vector<Estimate> estimates;
  std::vector<Mode> localization, manager;            // status timelines
  std::vector<std::pair<std::string, std::vector<Steer>>> commands;  // per ControlCommand topic
  std::vector<PathSnapshot> paths;                    // of the first Path topic
  std::vector<std::string> notes;                     // what was not in the recording
};

// Throws std::runtime_error naming the file when it cannot be read.
RunData read_run(const std::string& recording);

// (s, d) of a map point on the run's centre line (nearest segment; left positive).
std::pair<double, double> to_track(const RunData& d, double x, double y);

}  // namespace brickyard::report
