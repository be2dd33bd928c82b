// Nanoseconds per predict and per update of the pose filter under each update policy. The
// baseline beside ours is the naive filter's update (every fix fused, no selection).
// Exits 1 unless every benchmark ran and the three policies, given the same two agreeing fixes,
// accept both and land within 5 cm of each other (the baseline computes what ours does).
// usage: bench_fusion [--quick] [Google Benchmark's flags]
#include "estimation/common/update_selection.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

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

std::vector<Fix> two_agreeing_fixes() {
  std::vector<Fix> fixes(2);
  fixes[0] = {0, {1.55, 0.52}, {1.606, 0.05, 1.0}, 0.015};
  fixes[1] = {1, {1.52, 0.45}, {1.606, -0.05, 1.0}, 0.015};
  return fixes;
}

void BM_Update(benchmark::State& st) {
  const Policy policy = static_cast<Policy>(st.range(0));
  PoseFilter f = ready();
  const std::vector<Fix> fixes = two_agreeing_fixes();
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

// The three policies on the benchmark's epoch: each accepts both fixes, and the posteriors agree.
bool policies_agree() {
  PoseFilter results[3] = {ready(), ready(), ready()};
  bool ok = true;
  for (const Policy policy : {Policy::resilient, Policy::naive, Policy::gated}) {
    const EpochResult r = apply_fixes(results[static_cast<int>(policy)], two_agreeing_fixes(), policy, PolicyParams{});
    for (const bool accepted : r.accepted) ok = ok && accepted;
  }
  for (const PoseFilter& f : results) ok = ok && (f.state().head<2>() - results[1].state().head<2>()).norm() < 0.05;
  if (!ok) std::fprintf(stderr, "bench_fusion: the policies disagree on two agreeing fixes\n");
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<char*> args(argv, argv + argc);
  std::string min_time = "--benchmark_min_time=0.01";
  for (auto it = args.begin() + 1; it != args.end(); ++it)
    if (std::strcmp(*it, "--quick") == 0) {
      *it = min_time.data();  // each benchmark about 10 ms instead of Google Benchmark's 0.5 s
      break;
    }
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  if (benchmark::ReportUnrecognizedArguments(n, args.data())) return 2;
  const std::size_t ran = benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (ran != 4) std::fprintf(stderr, "bench_fusion: %zu of 4 benchmarks ran\n", ran);
  return ran == 4 && policies_agree() ? 0 : 1;
}
