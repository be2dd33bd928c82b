#pragma once
// Fault injection for simulated sensors: time windows, each of one kind, read from a graph
// parameter (a JSON array). Framework-free; each sensor node applies the active windows to its
// true measurement vector.
//
//   {"type": "bias",    "start_s": 498, "end_s": 505, "offset": [0.4, 0, 0]}   step bias
//   {"type": "drift",   "start_s": ..., "end_s": ..., "rate": [0.1, 0, 0]}     error grows, units/s
//   {"type": "noise",   ..., "factor": 10}                                      noise sigma x factor
//   {"type": "freeze",  ...}                                                    repeat the last output
//   {"type": "dropout", ...}                                                    no output at all
//   {"type": "spikes",  ..., "probability": 0.1, "magnitude": 5}               random outliers
//   {"type": "sigma",   ..., "factor": 0.1}                                     reported sigma x factor
//   {"type": "frame_loss", ..., "probability": 1}                              LiDAR frames lost
// Any window may also set "fix_type" (GNSS: 0 none, 1 single, 2 float, 3 fixed) while it is active.
#include "rng.hpp"

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::sim {

struct FaultWindow {
  std::string type;
  double start_s = 0, end_s = 0;
  std::vector<double> vec;    // offset (bias) or rate (drift)
  double factor = 1;          // noise, sigma
  double probability = 0;     // spikes, frame_loss
  double magnitude = 0;       // spikes
  std::optional<int> fix_type;
  bool active(double t) const { return t >= start_s && t < end_s; }
};

// What the active windows do to one sample.
struct FaultEffect {
  std::vector<double> offset;  // add to the measurement (bias + drift + spike)
  double noise_factor = 1;
  double sigma_factor = 1;
  bool freeze = false, drop = false;
  std::optional<int> fix_type;
};

class FaultError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class FaultSchedule {
 public:
  FaultSchedule() = default;
  // `json_text` is a JSON array of windows; `dims` the length of the measurement vector;
  // `allowed` the types this sensor supports. Errors name the JSON pointer of the culprit.
  FaultSchedule(const std::string& json_text, std::size_t dims, const std::vector<std::string>& allowed);
  const std::vector<FaultWindow>& windows() const { return w_; }
  bool empty() const { return w_.empty(); }
  // Effect at time t. Spikes and frame loss draw from rng (only while such a window is active,
  // so a schedule without them leaves the noise sequence untouched).
  FaultEffect at(double t, Rng& rng) const;

 private:
  std::vector<FaultWindow> w_;
  std::size_t dims_ = 0;
};

}  // namespace brickyard::sim
