#include "graph/diagnostics.hpp"

namespace brickyard::fw {

std::string format_diagnostics(const std::vector<Diagnostic>& d) {
  std::string out;
  for (const auto& x : d) out += "error: " + x.where + ": " + x.message + "\n";
  return out;
}

InvalidInput::InvalidInput(std::vector<Diagnostic> d)
    : std::runtime_error(format_diagnostics(d)), diags_(std::move(d)) {}

}  // namespace brickyard::fw
