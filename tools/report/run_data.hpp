#pragma once
// What the report draws, read from a run's recording (docs/recording.md): topics found by their
// message type, decoded into plain series. Framework-free apart from the SDK's message types.
#include <string>
#include <vector>

namespace brickyard::report {

struct Pose {
  double t, x, y, speed, s;  // s: along the centre line (VehicleState.s)
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
  double x, y, radius;
};

struct RunData {
  std::vector<double> left_x, left_y, right_x, right_y;  // track edges (closed)
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

}  // namespace brickyard::report
