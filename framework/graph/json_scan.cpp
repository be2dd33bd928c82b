#include "graph/json_scan.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <set>
#include <vector>

namespace brickyard::fw {

TextPosition position_of(const std::string& text, std::size_t byte_offset) {
  TextPosition p;
  for (std::size_t i = 0; i < byte_offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++p.line;
      p.column = 1;
    } else {
      ++p.column;
    }
  }
  return p;
}

// Index just past the string literal starting at text[i] == '"'.
static std::size_t skip_string(const std::string& text, std::size_t i) {
  for (++i; i < text.size(); ++i) {
    if (text[i] == '\\') ++i;
    else if (text[i] == '"') return i + 1;
  }
  return text.size();
}

std::optional<ScanFinding> find_excess_depth(const std::string& text, int max_depth) {
  int depth = 0;
  for (std::size_t i = 0; i < text.size();) {
    char c = text[i];
    if (c == '"') { i = skip_string(text, i); continue; }
    if (c == '{' || c == '[') {
      if (++depth > max_depth)
        return ScanFinding{i, "nesting deeper than " + std::to_string(max_depth) + " levels"};
    } else if (c == '}' || c == ']') {
      --depth;
    }
    ++i;
  }
  return std::nullopt;
}

std::optional<ScanFinding> find_duplicate_key(const std::string& text) {
  struct Frame {
    bool object;
    bool expect_key;
    std::set<std::string> keys;
  };
  std::vector<Frame> stack;
  for (std::size_t i = 0; i < text.size();) {
    char c = text[i];
    if (c == '"') {
      std::size_t end = skip_string(text, i);
      if (!stack.empty() && stack.back().object && stack.back().expect_key) {
        std::string key = text.substr(i + 1, end - i - 2);
        if (!stack.back().keys.insert(key).second) return ScanFinding{i, "duplicate key \"" + key + "\""};
        stack.back().expect_key = false;
      }
      i = end;
      continue;
    }
    if (c == '{') stack.push_back({true, true, {}});
    else if (c == '[') stack.push_back({false, false, {}});
    else if ((c == '}' || c == ']') && !stack.empty()) stack.pop_back();
    else if (c == ',' && !stack.empty() && stack.back().object) stack.back().expect_key = true;
    ++i;
  }
  return std::nullopt;
}

std::optional<ScanFinding> find_number_overflow(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '"') {
      i = skip_string(text, i);
      continue;
    }
    if (c == '-' || (c >= '0' && c <= '9')) {
      std::size_t end = i + 1;
      while (end < text.size() && (std::isdigit(static_cast<unsigned char>(text[end])) || text[end] == '.' || text[end] == 'e' ||
                                   text[end] == 'E' || text[end] == '+' || text[end] == '-'))
        ++end;
      const std::string token = text.substr(i, end - i);
      const double v = std::strtod(token.c_str(), nullptr);
      if (std::isinf(v)) return ScanFinding{i, "number " + (token.size() > 40 ? token.substr(0, 40) + "…" : token) + " is beyond what a double holds"};
      i = end;
      continue;
    }
    ++i;
  }
  return std::nullopt;
}

}  // namespace brickyard::fw
