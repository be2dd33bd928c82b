// Nanoseconds per predict and per update of the pose filter under each update policy. The
// baseline beside ours is the naive filter's update (every fix fused, no selection).
#include "estimation/common/update_selection.hpp"

#include <benchmark/benchmark.h>

using namespace brickyard::estimation;

namespace {

PoseFilter ready() {
  PoseFilter f;
  f.init(0, 0, 0.3, 0.1, 0.05);
  return f;
}

void BM_Predict(benchmark::State& st) {
  PoseFilter f = ready();
  for (auto _ : st) {
    f.predict(0.008, 70.0, 0.2);
    benchmark::DoNotOptimize(f.state());
  }
}
BENCHMARK(BM_Predict);

void BM_Update(benchmark::State& st) {
  const Policy policy = static_cast<Policy>(st.range(0));
  PoseFilter f = ready();
  std::vector<Fix> fixes(2);
  fixes[0] = {0, {1.55, 0.52}, {1.606, 0.05, 1.0}, 0.015};
  fixes[1] = {1, {1.52, 0.45}, {1.606, -0.05, 1.0}, 0.015};
  PolicyParams p;
  for (auto _ : st) {
    PoseFilter g = f;  // the same prior every time
    benchmark::DoNotOptimize(apply_fixes(g, fixes, policy, p));
  }
  st.SetLabel(policy == Policy::resilient ? "ours: resilient selection + 1 update"
              : policy == Policy::naive   ? "baseline: naive, 2 updates"
                                          : "baseline: gated, 2 gates + updates");
}
BENCHMARK(BM_Update)->Arg(static_cast<int>(Policy::resilient))->Arg(static_cast<int>(Policy::naive))->Arg(static_cast<int>(Policy::gated));

}  // namespace

BENCHMARK_MAIN();
