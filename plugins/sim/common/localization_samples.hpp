#pragma once
// A scored estimate per line, with the truth it was scored against, for looking into a run
// (where the estimate went off, what it claimed meanwhile): CSV written to PATH.part, renamed to
// PATH only when complete, so a run that dies leaves no half-written file under the name asked
// for. Framework-free; sim.localization_scorer writes it when `samples_file` is set.
#include <cstdio>
#include <string>

namespace brickyard::sim {

struct EstimateSample {
  double t = 0, x = 0, y = 0, yaw = 0;
  double xx = 0, xy = 0, yy = 0;  // the estimate's covariance over (x, y), m^2
  double yaw_var = 0;             // its yaw's variance, rad^2
  int status = 0, update_case = 0;
  double truth_x = 0, truth_y = 0;
};

class SampleLog {
 public:
  // Throws std::runtime_error naming the file when it cannot be opened.
  explicit SampleLog(std::string path);
  ~SampleLog();
  SampleLog(const SampleLog&) = delete;
  SampleLog& operator=(const SampleLog&) = delete;
  void add(const EstimateSample& s);
  // Closes and renames PATH.part to PATH; throws std::runtime_error naming the file on failure.
  void finish();

 private:
  std::string path_;
  std::FILE* f_ = nullptr;
};

}  // namespace brickyard::sim
