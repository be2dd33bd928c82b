#pragma once
// The newest sample of an input read by "latest value" nodes. Plugin-side (SDK), shared by the
// adapters of several areas.
#include <brickyard/context.hpp>

#include <memory>

namespace brickyard::plugins {

// Drains the queue so the run's summary does not count the skipped samples as dropped; with
// nothing new, the last sample seen (null before the first).
template <class T> std::shared_ptr<const T> newest(Input<T>& in) {
  auto v = in.take();
  return v.empty() ? in.latest() : v.back();
}

}  // namespace brickyard::plugins
