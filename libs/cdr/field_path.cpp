#include "cdr/field_path.hpp"

#include <cctype>
#include <stdexcept>

namespace brickyard::cdr {

FieldPath parse_field_path(const std::string& text) {
  FieldPath p;
  p.text = text;
  if (text.empty()) throw std::invalid_argument("an empty field path");
  if (text.size() > 256) throw std::invalid_argument("a field path of " + std::to_string(text.size()) + " characters (at most 256)");
  std::size_t i = 0;
  while (i < text.size()) {
    FieldPath::Step s;
    const std::size_t start = i;
    while (i < text.size() && (std::isalnum(static_cast<unsigned char>(text[i])) || text[i] == '_')) ++i;
    s.member = text.substr(start, i - start);
    if (s.member.empty()) throw std::invalid_argument(text + ": expected a member name at character " + std::to_string(start + 1));
    while (i < text.size() && text[i] == '[') {
      const std::size_t close = text.find(']', i);
      if (close == std::string::npos) throw std::invalid_argument(text + ": a '[' without its ']'");
      const std::string in = text.substr(i + 1, close - i - 1);
      if (in == "*") s.index.push_back(FieldPath::kEvery);
      else if (!in.empty() && in.size() <= 9 && in.find_first_not_of("0123456789") == std::string::npos) s.index.push_back(std::stoll(in));
      else throw std::invalid_argument(text + ": [" + in + "]: expected an index (at most 9 digits) or *");
      i = close + 1;
    }
    p.steps.push_back(std::move(s));
    if (i < text.size()) {
      if (text[i] != '.') throw std::invalid_argument(text + ": unexpected '" + std::string(1, text[i]) + "' at character " + std::to_string(i + 1));
      if (++i == text.size()) throw std::invalid_argument(text + ": ends with '.'");
    }
  }
  return p;
}

std::string concrete(const FieldPath& path, const std::vector<std::int64_t>& every) {
  std::string s;
  std::size_t k = 0;
  for (const auto& st : path.steps) {
    s += (s.empty() ? "" : ".") + st.member;
    for (auto ix : st.index) {
      if (ix != FieldPath::kEvery) s += "[" + std::to_string(ix) + "]";
      else s += k < every.size() ? "[" + std::to_string(every[k++]) + "]" : "[*]";
    }
  }
  return s;
}

namespace {

struct Walker {
  const FieldPath& path;
  std::vector<FieldValue>& out;
  std::string& missing;
  std::vector<std::int64_t> every;

  void note() {
    if (missing.empty()) missing = concrete(path, every);
  }
  void member(const nlohmann::json& v, std::size_t step) {
    if (step == path.steps.size()) return out.push_back({&v, every});
    const auto it = v.is_object() ? v.find(path.steps[step].member) : v.end();
    if (!v.is_object() || it == v.end()) return note();
    index(*it, step, 0);
  }
  void index(const nlohmann::json& v, std::size_t step, std::size_t k) {
    const auto& st = path.steps[step];
    if (k == st.index.size()) return member(v, step + 1);
    if (!v.is_array()) return note();
    const std::int64_t ix = st.index[k];
    if (ix == FieldPath::kEvery) {
      for (std::size_t e = 0; e < v.size(); ++e) {
        every.push_back(static_cast<std::int64_t>(e));
        index(v[e], step, k + 1);
        every.pop_back();
      }
    } else if (static_cast<std::size_t>(ix) < v.size()) {
      index(v[static_cast<std::size_t>(ix)], step, k + 1);
    } else {
      note();
    }
  }
};

}  // namespace

void field_values(const nlohmann::json& sample, const FieldPath& path, std::vector<FieldValue>& out, std::string& missing) {
  Walker w{path, out, missing, {}};
  w.member(sample, 0);
}

}  // namespace brickyard::cdr
