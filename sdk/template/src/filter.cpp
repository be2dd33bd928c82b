#include "filter.hpp"

double LowPass::update(double x) {
  y_ = primed_ ? y_ + alpha_ * (x - y_) : x;
  primed_ = true;
  return y_;
}
