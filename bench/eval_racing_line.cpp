// Issue 7 (in progress): our minimum-curvature racing line beside TUM's (data/racelines/) on the
// tracks in data/tracks/: summed squared curvature (Σ κ² ds, Menger curvature) and the optimiser's
// time. TUM's lines put the car's centre 0.6 m from the edges, so the comparison gives ours the
// same room (margin 0.6 m); the default margin for driving (1.5 m: half the AV-21's width and a
// margin) is shown beside it. Prints the table of docs/planning.md.
#include "common/min_curvature.hpp"
#include "common/track.hpp"

#include <chrono>
#include <cstdio>
#include <string>

using namespace brickyard;

int main() {
  const std::string data = std::string(BRICKYARD_SOURCE_DIR) + "/data";
  std::printf("| track | points | centre line Σκ²ds | TUM Σκ²ds | ours, margin 0.6 m | ours / TUM | time | ours, margin 1.5 m | time |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const char* name : {"IMS", "Monza", "Spielberg", "Hockenheim"}) {
    const auto c = sim::load_centerline_csv(data + "/tracks/" + name + ".csv");
    const auto tum = sim::load_xy_csv(data + "/racelines/" + name + ".csv");
    const planning::ClosedLine line{c.x, c.y, c.width_left, c.width_right};
    double cost[2], ms[2];
    for (int k = 0; k < 2; ++k) {
      planning::MinCurvatureParams p;
      p.margin = k == 0 ? 0.6 : 1.5;
      const auto t0 = std::chrono::steady_clock::now();
      const auto r = planning::min_curvature_line(line, p);
      ms[k] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      cost[k] = planning::summed_squared_curvature(r.x, r.y);
    }
    const double t = planning::summed_squared_curvature(tum.x, tum.y);
    std::printf("| %s | %zu | %.5f | %.5f | %.5f | %.3f | %.0f ms | %.5f | %.0f ms |\n", name, c.x.size(),
                planning::summed_squared_curvature(c.x, c.y), t, cost[0], cost[0] / t, ms[0], cost[1], ms[1]);
  }
  return 0;
}
