#pragma once
// The algorithm: an exponential low-pass filter. It knows nothing of Brickyard.

class LowPass {
 public:
  explicit LowPass(double alpha) : alpha_(alpha) {}
  double update(double x);

 private:
  double alpha_;
  double y_ = 0;
  bool primed_ = false;
};
