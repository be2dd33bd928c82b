#pragma once
// Checks on raw JSON text that a DOM parser cannot make: nesting depth (before parsing, so
// absurd input cannot exhaust the stack) and duplicate object keys (which parsers keep silently).
#include <cstddef>
#include <optional>
#include <string>

namespace brickyard::fw {

struct TextPosition {
  std::size_t line = 1, column = 1;
};
TextPosition position_of(const std::string& text, std::size_t byte_offset);

struct ScanFinding {
  std::size_t offset;
  std::string message;
};

// First position where nesting exceeds max_depth, if any. Works on invalid JSON too.
std::optional<ScanFinding> find_excess_depth(const std::string& text, int max_depth);
// How deep a value given on the command line (--set, --arg) may nest: a parameter's value, placed
// inside a graph whose files may nest 64 deep. Deeper, the JSON parser's recursion is the bound.
constexpr int kMaxValueDepth = 32;
// First duplicate key in any object. Expects syntactically valid JSON.
std::optional<ScanFinding> find_duplicate_key(const std::string& text);
// First number no double holds (1e999): the parser says only "number overflow", not where.
std::optional<ScanFinding> find_number_overflow(const std::string& text);

}  // namespace brickyard::fw
