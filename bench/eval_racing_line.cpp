// Issue 7: our racing lines beside TUM's (data/racelines/) on the tracks in data/tracks/: summed
// squared curvature (Σ κ² ds, Menger curvature), the lap time under the same limits (curvature
// point by point, and averaged over 30 m as the driving stack sees it) and the optimisers' time — the minimum-curvature line (min_curvature.hpp) and its minimum-time
// refinement (min_time.hpp). TUM's lines put the car's centre 0.6 m from the edges, so the
// comparison gives ours the same room (margin 0.6 m); the default margin for driving (1.5 m: half
// the AV-21's width and a margin) is shown beside it. Prints the tables of docs/planning.md.
#include "planning/common/min_curvature.hpp"
#include "planning/common/line_setup.hpp"
#include "planning/common/min_time.hpp"
#include "motion/speed_profile.hpp"
#include "motion/vehicle_limits.hpp"
#include "track/centre_line.hpp"
#include "vehicle/vehicle.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

using namespace brickyard;

namespace {
double since_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

double length(const std::vector<double>& x, const std::vector<double>& y) {
  double l = 0;
  for (std::size_t i = 0; i < x.size(); ++i) l += std::hypot(x[(i + 1) % x.size()] - x[i], y[(i + 1) % x.size()] - y[i]);
  return l;
}

}  // namespace

int main() {
  // The AV-21 (data/vehicles/av21.json through motion::vehicle_limits: 9 kN drive and 370 kW on
  // 815 kg, lateral grip and brakes 15 m/s², drag ρ Cd A / 2m; downforce ignored).
  const motion::VehicleLimits car =
      motion::vehicle_limits(vehicle::load_vehicle(std::string(BRICKYARD_SOURCE_DIR) + "/data/vehicles/av21.json"));
  std::vector<std::string> times, refined, smoothed;
  const std::string data = std::string(BRICKYARD_SOURCE_DIR) + "/data";
  std::printf("| track | points | centre line Σκ²ds | TUM Σκ²ds | ours, margin 0.6 m | ours / TUM | time | ours, margin 1.5 m | time |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const char* name : {"IMS", "Monza", "Spielberg", "Hockenheim"}) {
    const auto c = track::load_centerline_csv(data + "/tracks/" + name + ".csv");
    const auto tum = track::load_xy_csv(data + "/racelines/" + name + ".csv");
    const planning::ClosedLine line{c.x, c.y, c.width_left, c.width_right};
    planning::MinCurvatureResult ours;  // margin 0.6 m
    double cost[2], ms[2];
    for (int k = 0; k < 2; ++k) {
      planning::MinCurvatureParams p;
      p.margin = k == 0 ? 0.6 : 1.5;
      const auto t0 = std::chrono::steady_clock::now();
      auto r = planning::min_curvature_line(line, p);
      ms[k] = since_ms(t0);
      cost[k] = planning::summed_squared_curvature(r.x, r.y);
      if (k == 0) ours = std::move(r);
    }
    planning::MinTimeParams mp;
    mp.margin = 0.6;
    const auto t0 = std::chrono::steady_clock::now();
    const auto fast = planning::min_time_refine(line, ours.offset, car, mp);
    const double ms_refine = since_ms(t0);
    mp.averaged_over = 0;  // the point-wise lap time alone in the objective (the refinement's first form)
    const auto pointwise = planning::min_time_refine(line, ours.offset, car, mp);
    const double t = planning::summed_squared_curvature(tum.x, tum.y);
    const double lt_tum = planning::lap_time(tum.x, tum.y, car), lt_ours = planning::lap_time(ours.x, ours.y, car);
    char row[300];
    std::snprintf(row, sizeof row, "| %s | %.2f s | %.2f s | %+.2f s | %.1f m | %.1f m |", name, lt_tum, lt_ours, lt_ours - lt_tum,
                  length(tum.x, tum.y), length(ours.x, ours.y));
    times.push_back(row);
    std::snprintf(row, sizeof row, "| %s | %.5f | %.5f | %.3f | %.2f s | %.2f s | %+.2f s | %.1f m | %d | %.0f ms | %.0f ms | %.5f, %.2f s |", name,
                  t, fast.energy, fast.energy / t, lt_tum, fast.time, fast.time - lt_tum, length(fast.x, fast.y), fast.iterations,
                  ms_refine, ms[0] + ms_refine, pointwise.energy, pointwise.time);
    refined.push_back(row);
    const double avg_tum = planning::lap_time(tum.x, tum.y, car, 30);
    std::snprintf(row, sizeof row, "| %s | %.2f s | %.2f s | %.2f s | %.2f s | %+.2f s |", name, avg_tum,
                  planning::lap_time(ours.x, ours.y, car, 30), planning::lap_time(pointwise.x, pointwise.y, car, 30),
                  fast.averaged_time, fast.averaged_time - avg_tum);
    smoothed.push_back(row);
    std::printf("| %s | %zu | %.5f | %.5f | %.5f | %.3f | %.0f ms | %.5f | %.0f ms |\n", name, c.x.size(),
                planning::summed_squared_curvature(c.x, c.y), t, cost[0], cost[0] / t, ms[0], cost[1], ms[1]);
  }
  std::printf("\nLap time under the same limits (ggv ellipse, drag, power; speed_profile.hpp):\n\n");
  std::printf("| track | TUM's line | ours, margin 0.6 m | ours − TUM | TUM's length | our length |\n|---|---|---|---|---|---|\n");
  for (const auto& r : times) std::printf("%s\n", r.c_str());
  std::printf("\nThe minimum-time refinement of ours (margin 0.6 m, MinTimeParams' defaults; min_time.hpp):\n\n");
  std::printf("| track | TUM Σκ²ds | refined Σκ²ds | refined / TUM | TUM's lap | refined lap | refined − TUM | refined length "
              "| steps | refine time | with the min-curvature line | point-wise only: Σκ²ds, lap |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& r : refined) std::printf("%s\n", r.c_str());
  std::printf("\nLap times with the curvature averaged over 30 m (lap_time(..., 30): as brickyard-plan --profile writes "
              "the line and the driving stack sees it):\n\n");
  std::printf("| track | TUM's line | ours, margin 0.6 m | refined point-wise only | refined | refined − TUM |\n"
              "|---|---|---|---|---|---|\n");
  for (const auto& r : smoothed) std::printf("%s\n", r.c_str());
  return 0;
}
