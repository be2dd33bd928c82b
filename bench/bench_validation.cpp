// How long `brickyard validate` takes on large graphs (target: 100 000 nodes in at
// most 2 s, and linear in the graph's size), beside reading the same JSON with nlohmann::json in
// this process — the floor any validator pays. Chains of testing plugins (a scripted source,
// transforms, an assert sink), 10 000 to 100 000 nodes (--quick: 1 000 and 10 000); medians of 3.
// Exits 1 when validate refuses a graph or the JSON read back is not the graph written.
// usage: bench_validation [--quick]
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string chain(int n) {
  nlohmann::json g;
  g["nodes"]["src"] = {{"plugin", "testing.scripted_source"}};
  g["nodes"]["check"] = {{"plugin", "testing.assert_sink"}};
  std::string prev = "src";
  for (int i = 0; i < n - 2; ++i) {
    const std::string t = "t" + std::to_string(i);
    g["nodes"][t] = {{"plugin", "testing.transform"}};
    g["wires"].push_back({{"from", prev + ".out"}, {"to", t + ".in"}});
    prev = t;
  }
  g["wires"].push_back({{"from", prev + ".out"}, {"to", "check.in"}});
  return g.dump();
}
}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const std::string by = BRICKYARD_HOST, dir = "/tmp/bench_validation";
  fs::create_directories(dir);
  std::printf("brickyard validate on a chain of N nodes (medians of 3)\n%10s %14s %14s %16s\n", "N", "ours s", "JSON parse s", "ours µs a node");
  for (int n : quick ? std::vector<int>{1000, 10000} : std::vector<int>{10000, 30000, 100000}) {
    const std::string text = chain(n), file = dir + "/chain_" + std::to_string(n) + ".json";
    std::ofstream(file) << text;
    std::vector<double> ours, parse;
    for (int r = 0; r < 3; ++r) {
      auto t0 = Clock::now();
      if (std::system((by + " validate " + file + " > /dev/null").c_str()) != 0) return std::printf("validate failed on %s\n", file.c_str()), 1;
      ours.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      t0 = Clock::now();
      std::ifstream in(file);
      const auto j = nlohmann::json::parse(in);
      parse.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
      if (j.size() != 2 || j["nodes"].size() != static_cast<std::size_t>(n))
        return std::printf("%s read back is not the graph written\n", file.c_str()), 1;
    }
    std::printf("%10d %14.3f %14.3f %16.2f\n", n, median(ours), median(parse), 1e6 * median(ours) / n);
  }
  std::printf("target: 100 000 nodes in at most 2 s; linear: the time a node roughly constant down the column\n");
  return 0;
}
