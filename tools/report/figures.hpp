#pragma once
// The report's figures (a tour: docs/report.md): each writes its data files into the report's
// work folder and returns the gnuplot commands drawing <name>.svg from them. A figure whose data
// the run did not record is left out.
#include "run_data.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace brickyard::report {

struct Figure {
  std::string name, title, caption, script;  // script: gnuplot commands drawing <name>.svg
};

// The report's work folder: figures' data files, their SVGs and the gnuplot script.
class Writer {
 public:
  explicit Writer(std::filesystem::path dir) : dir_(std::move(dir)) {}
  std::filesystem::path file(const std::string& name) const { return dir_ / name; }
  std::ofstream open(const std::string& name) const {
    std::ofstream f(file(name));
    f.precision(10);
    return f;
  }

 private:
  std::filesystem::path dir_;
};

// Every figure the run's data allows, in the report's order. summary: the run's summary.json
// (the fusion's thresholds, the road graph's nodes).
std::vector<Figure> figures(const RunData& d, const nlohmann::json& summary, const Writer& w);

}  // namespace brickyard::report
