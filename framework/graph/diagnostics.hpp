#pragma once
// Bad input is collected, not thrown at the first problem: a user fixes a graph in one pass.
#include <stdexcept>
#include <string>
#include <vector>

namespace brickyard::fw {

struct Diagnostic {
  std::string where;    // "graph.json:3:14", "graph.json#/nodes/ekf/params/delta_m", "--set", a library path
  std::string message;
};

// Invalid input: the CLI prints every diagnostic and exits with code 2.
class InvalidInput : public std::runtime_error {
 public:
  explicit InvalidInput(std::vector<Diagnostic> d);
  InvalidInput(std::string where, std::string message)
      : InvalidInput(std::vector<Diagnostic>{Diagnostic{std::move(where), std::move(message)}}) {}
  const std::vector<Diagnostic>& diagnostics() const { return diags_; }

 private:
  std::vector<Diagnostic> diags_;
};

class Diagnostics {
 public:
  void add(std::string where, std::string message) { items_.push_back({std::move(where), std::move(message)}); }
  void append(const Diagnostics& o) { items_.insert(items_.end(), o.items_.begin(), o.items_.end()); }
  bool empty() const { return items_.empty(); }
  const std::vector<Diagnostic>& items() const { return items_; }
  void raise_if_any() const {
    if (!items_.empty()) throw InvalidInput(items_);
  }

 private:
  std::vector<Diagnostic> items_;
};

std::string format_diagnostics(const std::vector<Diagnostic>& d);

}  // namespace brickyard::fw
