#pragma once
// JSON written as text as it goes, for the live scene's messages (scene_*.cpp). Why not
// nlohmann::json objects: a scene message built as objects (a std::map and a string per key,
// copied into its parent, then dumped) cost the run 20 to 50 us, and the scene sends a hundred
// and fifty a second of sim time (docs/live.md, "Cost"). Commas are placed from the last character written:
// none after an opening bracket or a key's colon, one before anything else.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>

namespace brickyard::fw {

class JsonText {
 public:
  JsonText& open(char bracket) {  // '{' or '['
    comma();
    out_.push_back(bracket);
    return *this;
  }
  JsonText& close(char bracket) {  // '}' or ']'
    out_.push_back(bracket);
    return *this;
  }
  JsonText& key(std::string_view k) {
    str(k);
    out_.push_back(':');
    return *this;
  }
  // JSON has no NaN or infinity, and a diverging estimate is no place to draw: 0 there. The
  // shortest text that reads back as the same double, or `decimals` (0 to 6) fixed digits,
  // rounded to nearest: written as an integer with a point put in (to_chars' fixed precision
  // took 50 ns a number, the bulk of a path of a thousand points).
  JsonText& num(double v, int decimals = -1) {
    comma();
    if (!std::isfinite(v)) v = 0.0;
    char b[40];
    char* end = b;
    static constexpr double kScale[] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6};
    if (decimals >= 0 && decimals <= 6 && std::fabs(v) * kScale[decimals] < 1e15) {
      const long long n = std::llround(v * kScale[decimals]);
      const unsigned long long a = n < 0 ? 0ull - static_cast<unsigned long long>(n) : static_cast<unsigned long long>(n);
      // The digits, with zeros before them up to decimals + 1 (0.005: "0005"), the point put
      // before the last `decimals`.
      char digits[32];
      int m = 0;
      char raw[24];
      const int len = static_cast<int>(std::to_chars(raw, raw + sizeof raw, a).ptr - raw);
      for (int pad = decimals + 1 - len; pad > 0; --pad) digits[m++] = '0';
      for (int i = 0; i < len; ++i) digits[m++] = raw[i];
      if (n < 0) *end++ = '-';
      for (int i = 0; i < m; ++i) {
        if (i == m - decimals) *end++ = '.';
        *end++ = digits[i];
      }
    } else {
      const auto r = decimals < 0 ? std::to_chars(b, b + sizeof b, v) : std::to_chars(b, b + sizeof b, v, std::chars_format::fixed, decimals);
      end = r.ec == std::errc() ? r.ptr : (*b = '0', b + 1);
    }
    out_.append(b, end);
    return *this;
  }
  JsonText& uint(std::uint64_t v) {
    comma();
    char b[24];
    out_.append(b, std::to_chars(b, b + sizeof b, v).ptr);
    return *this;
  }
  JsonText& boolean(bool v) {
    comma();
    out_.append(v ? "true" : "false");
    return *this;
  }
  JsonText& str(std::string_view s) {
    comma();
    out_.push_back('"');
    for (const char c : s) {
      if (c == '"' || c == '\\') {
        out_.push_back('\\');
        out_.push_back(c);
      } else if (static_cast<unsigned char>(c) < 0x20) {
        char u[8];
        std::snprintf(u, sizeof u, "\\u%04x", static_cast<unsigned>(c));
        out_.append(u);
      } else {
        out_.push_back(c);
      }
    }
    out_.push_back('"');
    return *this;
  }
  // Text that is JSON already (an array or object written by another JsonText).
  JsonText& raw(std::string_view json) {
    comma();
    out_.append(json);
    return *this;
  }
  const std::string& text() const { return out_; }
  std::string take() { return std::move(out_); }

 private:
  void comma() {
    if (!out_.empty() && out_.back() != '{' && out_.back() != '[' && out_.back() != ':') out_.push_back(',');
  }
  std::string out_;
};

}  // namespace brickyard::fw
