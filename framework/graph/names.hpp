#pragma once
// Names in graphs, flags and manifests, checked in one pass without std::regex: a regex match is
// recursive in libstdc++ and overflowed the stack on a name of 20 000 characters.
// Names are bounded too, and a message quotes at most the first characters of one.
#include <cstddef>
#include <string>
#include <string_view>

namespace brickyard::fw {

inline constexpr std::size_t kMaxNameLength = 128;

// [A-Za-z_][A-Za-z0-9_]*, at most kMaxNameLength characters.
inline bool is_identifier(std::string_view s) {
  if (s.empty() || s.size() > kMaxNameLength) return false;
  auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; };
  if (!alpha(s[0])) return false;
  for (char c : s)
    if (!alpha(c) && !(c >= '0' && c <= '9')) return false;
  return true;
}

// Lower-case words [a-z][a-z0-9_]* joined by dots: at least `min_words`, at most `max_words` of
// them (a plugin's name area.name: 2 or more; new-plugin's name: 1 or 2), at most kMaxNameLength.
inline bool is_dotted_name(std::string_view s, std::size_t min_words, std::size_t max_words) {
  if (s.empty() || s.size() > kMaxNameLength) return false;
  std::size_t words = 0, at = 0;
  while (at <= s.size()) {
    const std::size_t dot = std::min(s.find('.', at), s.size());
    const std::string_view w = s.substr(at, dot - at);
    if (w.empty() || !(w[0] >= 'a' && w[0] <= 'z')) return false;
    for (char c : w)
      if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
    ++words;
    at = dot + 1;
  }
  return words >= min_words && words <= max_words;
}

// A name as a message quotes it: whole when short, else its start and its length.
inline std::string quoted_name(std::string_view s) {
  if (s.size() <= 60) return std::string(s);
  return std::string(s.substr(0, 40)) + "… (" + std::to_string(s.size()) + " characters)";
}

}  // namespace brickyard::fw
