#include "graph/diagnostics.hpp"

namespace brickyard::fw {

namespace {
// The first problems are said one per line; past these, a count. A file of a million duplicate
// wires printed a million lines (123 MB); nobody fixes the 51st before the first.
constexpr std::size_t kShown = 50;
}  // namespace

std::string format_diagnostics(const std::vector<Diagnostic>& d) {
  std::string out;
  for (std::size_t i = 0; i < d.size() && i < kShown; ++i) out += "error: " + d[i].where + ": " + d[i].message + "\n";
  if (d.size() > kShown)
    out += "error: and " + std::to_string(d.size() - kShown) + " more problems (" + std::to_string(d.size()) +
           " in all; the first " + std::to_string(kShown) + " above)\n";
  return out;
}

InvalidInput::InvalidInput(std::vector<Diagnostic> d)
    : std::runtime_error(format_diagnostics(d)), diags_(std::move(d)) {}

}  // namespace brickyard::fw
