#include "localization_samples.hpp"

#include <cmath>
#include <stdexcept>

namespace brickyard::sim {

SampleLog::SampleLog(std::string path) : path_(std::move(path)) {
  f_ = std::fopen((path_ + ".part").c_str(), "w");
  if (!f_) throw std::runtime_error(path_ + ": cannot write the samples (" + path_ + ".part would not open)");
  std::fputs("t,x,y,yaw,cov_xx,cov_xy,cov_yy,var_yaw,status,update_case,truth_x,truth_y,error_m\n", f_);
}

SampleLog::~SampleLog() {
  if (!f_) return;
  std::fclose(f_);
  std::remove((path_ + ".part").c_str());
}

void SampleLog::add(const EstimateSample& s) {
  if (!f_) return;
  std::fprintf(f_, "%.4f,%.4f,%.4f,%.5f,%.6g,%.6g,%.6g,%.6g,%d,%d,%.4f,%.4f,%.4f\n", s.t, s.x, s.y, s.yaw, s.xx, s.xy, s.yy, s.yaw_var, s.status,
               s.update_case, s.truth_x, s.truth_y, std::hypot(s.x - s.truth_x, s.y - s.truth_y));
}

void SampleLog::finish() {
  if (!f_) return;
  const bool written = std::fflush(f_) == 0 && !std::ferror(f_);
  std::fclose(f_);
  f_ = nullptr;
  const std::string part = path_ + ".part";
  if (!written || std::rename(part.c_str(), path_.c_str()) != 0) {
    std::remove(part.c_str());
    throw std::runtime_error(path_ + ": writing the samples failed (disk full, or the rename from " + part + ")");
  }
}

}  // namespace brickyard::sim
