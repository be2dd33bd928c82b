#include "expectations.hpp"

#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

namespace brickyard::testing {
namespace {

using nlohmann::json;

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::string window_text(double a, double b) {
  if (std::isinf(a) && std::isinf(b)) return "the whole run";
  return "[" + (std::isinf(a) ? std::string("start") : num(a) + " s") + ", " + (std::isinf(b) ? std::string("end") : num(b) + " s") + "]";
}

std::string show(const json& v) { return v.is_number() ? num(v.get<double>()) : v.dump(); }

bool has_every(const cdr::FieldPath& p) {
  for (const auto& s : p.steps)
    for (auto i : s.index)
      if (i == cdr::FieldPath::kEvery) return true;
  return false;
}

// Two numbers, lo <= hi: a range or a window.
std::pair<double, double> pair_of(const json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    throw std::invalid_argument(where + ": expected [low, high], found " + v.dump());
  const double a = v[0].get<double>(), b = v[1].get<double>();
  if (!std::isfinite(a) || !std::isfinite(b) || a > b) throw std::invalid_argument(where + ": expected finite low <= high, found " + v.dump());
  return {a, b};
}

std::vector<cdr::FieldPath> paths(const json& v, const std::string& where, const cdr::CdrJson& idl, const std::string& type,
                                  bool several, std::vector<std::string>* kinds) {
  std::vector<std::string> texts;
  if (v.is_string()) texts.push_back(v.get<std::string>());
  else if (several && v.is_array() && !v.empty() && v.size() <= 3) {
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!v[i].is_string()) throw std::invalid_argument(where + "/" + std::to_string(i) + ": expected a field path");
      texts.push_back(v[i].get<std::string>());
    }
  } else {
    throw std::invalid_argument(where + ": expected a field path" + std::string(several ? " or a list of 1 to 3 of them" : "") + ", found " + v.dump());
  }
  std::vector<cdr::FieldPath> out;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const std::string w = v.is_array() ? where + "/" + std::to_string(i) : where;
    try {
      out.push_back(cdr::parse_field_path(texts[i]));
      kinds->push_back(idl.field_kind(type, out.back()));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(w + ": " + e.what());
    }
  }
  return out;
}

// The whole list's shape: a list of 1 to 10000.
void check_spec_list(const json& spec) {
  if (!spec.is_array()) throw std::invalid_argument(": expected a list of expectations, found " + spec.dump().substr(0, 80));
  if (spec.empty()) throw std::invalid_argument(": no expectation (a check that checks nothing cannot fail)");
  if (spec.size() > 10000) throw std::invalid_argument(": more than 10000 expectations");
}

// An expectation's shape: an object of known keys.
void check_known_keys(const json& x, const std::string& w) {
  static const std::set<std::string> known = {"field", "range", "equals", "values", "tolerance", "increasing", "nondecreasing",
                                              "decreasing", "nonincreasing", "near", "away_from", "always", "eventually", "count",
                                              "rate_hz", "age_s"};
  if (!x.is_object()) throw std::invalid_argument(w + ": expected an object, found " + x.dump().substr(0, 80));
  for (const auto& [key, v] : x.items())
    if (!known.count(key))
      throw std::invalid_argument(w + "/" + key + ": unknown; an expectation takes field with one of range, equals "
                                  "(tolerance), values (tolerance), increasing, nondecreasing, decreasing, nonincreasing, near, away_from, "
                                  "and always or eventually; or count, rate_hz, age_s");
}

// count, rate_hz or age_s: the stream's, not a field's.
void parse_stream_check(const json& x, Expectation& e, const cdr::CdrJson& idl, const std::string& type) {
  const std::string& w = e.where;
  const char* key = x.contains("count") ? "count" : x.contains("rate_hz") ? "rate_hz" : "age_s";
  if (x.size() != 1) throw std::invalid_argument(w + ": count, rate_hz and age_s stand alone");
  e.kind = x.contains("count") ? Expectation::Kind::count : x.contains("rate_hz") ? Expectation::Kind::rate : Expectation::Kind::age;
  std::tie(e.lo, e.hi) = pair_of(x.at(key), w + "/" + key);
  if (e.kind == Expectation::Kind::age) {
    std::string kind;
    try {
      kind = idl.field_kind(type, cdr::parse_field_path("header.stamp_ns"));
    } catch (const std::invalid_argument&) {
    }
    if (kind != "number") throw std::invalid_argument(w + "/age_s: " + type + " has no header.stamp_ns to age from");
  }
  e.text = e.kind == Expectation::Kind::count ? "count within [" + num(e.lo) + ", " + num(e.hi) + "]"
           : e.kind == Expectation::Kind::rate ? "rate within [" + num(e.lo) + ", " + num(e.hi) + "] Hz"
                                                : "age (arrival less header.stamp_ns) within [" + num(e.lo) + ", " + num(e.hi) + "] s";
}

// Throws unless every one of e's fields (kinds: theirs) is a number.
void need_numbers(const Expectation& e, const std::vector<std::string>& kinds, const char* key) {
  for (std::size_t i = 0; i < kinds.size(); ++i)
    if (kinds[i] != "number")
      throw std::invalid_argument(e.where + "/" + key + ": " + e.fields[i].text + " is a " + kinds[i] + ", not a number");
}

// The JSON kind of a value, as CdrJson::field_kind names a field's ("?": none of them).
std::string kind_of(const json& v) { return v.is_number() ? "number" : v.is_string() ? "string" : v.is_boolean() ? "boolean" : "?"; }

// The optional tolerance of equals or values, allowed for a number only.
void parse_tolerance(const json& x, Expectation& e, bool for_number) {
  if (!x.contains("tolerance")) return;
  if (!x["tolerance"].is_number() || !(x["tolerance"].get<double>() >= 0) || !for_number)
    throw std::invalid_argument(e.where + "/tolerance: expected a number >= 0, for a number");
  e.tolerance = x["tolerance"].get<double>();
}

void parse_equals(const json& x, Expectation& e, const std::vector<std::string>& kinds) {
  const std::string& w = e.where;
  const std::string& f = e.fields[0].text;
  e.test = Expectation::Test::equals;
  e.equals = x["equals"];
  const std::string want = kind_of(e.equals);
  if (want != kinds[0]) throw std::invalid_argument(w + "/equals: " + f + " is a " + kinds[0] + "; found " + e.equals.dump().substr(0, 80));
  parse_tolerance(x, e, want == "number");
  e.text = f + " equals " + show(e.equals) + (e.tolerance > 0 ? " within " + num(e.tolerance) : "");
}

void parse_values(const json& x, Expectation& e, const std::vector<std::string>& kinds) {
  const std::string& w = e.where;
  const std::string& f = e.fields[0].text;
  e.test = Expectation::Test::values;
  e.equals = x["values"];
  if (has_every(e.fields[0])) throw std::invalid_argument(w + "/values: " + f + ": one value a sample, no [*]");
  if (!e.equals.is_array() || e.equals.empty() || e.equals.size() > 100000)
    throw std::invalid_argument(w + "/values: expected a list of the first samples' values");
  for (std::size_t i = 0; i < e.equals.size(); ++i) {
    const json& v = e.equals[i];
    const std::string want = kind_of(v);
    if (want != kinds[0])
      throw std::invalid_argument(w + "/values/" + std::to_string(i) + ": " + f + " is a " + kinds[0] + "; found " +
                                  v.dump().substr(0, 80));
  }
  parse_tolerance(x, e, kinds[0] == "number");
  e.text = f + " of the first " + std::to_string(e.equals.size()) + " samples " + e.equals.dump().substr(0, 60);
}

// increasing, nondecreasing, decreasing or nonincreasing.
void parse_monotonic(const json& x, Expectation& e, const std::vector<std::string>& kinds) {
  const char* key = x.contains("increasing")      ? "increasing"
                    : x.contains("nondecreasing") ? "nondecreasing"
                    : x.contains("decreasing")    ? "decreasing"
                                                  : "nonincreasing";
  need_numbers(e, kinds, key);
  if (x[key] != true) throw std::invalid_argument(e.where + "/" + key + ": expected true");
  const std::string k = key;
  e.test = k == "increasing" ? Expectation::Test::increasing : k == "nondecreasing" ? Expectation::Test::nondecreasing
           : k == "decreasing" ? Expectation::Test::decreasing : Expectation::Test::nonincreasing;
  e.text = e.fields[0].text + (has_every(e.fields[0]) ? " along each sample " : " sample to sample ") + key;
}

// Every point the fields make (element by element along a [*]) at least "beyond" from a
// fixed one: a path that keeps clear of an obstacle, a car that stays off a pylon.
void parse_away_from(const json& x, Expectation& e, const std::vector<std::string>& kinds) {
  const std::string& w = e.where;
  need_numbers(e, kinds, "away_from");
  e.test = Expectation::Test::away_from;
  const json& a = x["away_from"];
  if (!a.is_object() || a.size() != 2 || !a.contains("point") || !a.contains("beyond") || !a["point"].is_array() ||
      !a["beyond"].is_number() || !(a["beyond"].get<double>() >= 0) || !std::isfinite(a["beyond"].get<double>()))
    throw std::invalid_argument(w + "/away_from: expected {\"point\": [X, ...], \"beyond\": DISTANCE >= 0}");
  if (a["point"].size() != e.fields.size())
    throw std::invalid_argument(w + "/away_from/point: " + std::to_string(a["point"].size()) + " coordinates against " +
                                std::to_string(e.fields.size()) + " fields");
  for (std::size_t i = 0; i < e.fields.size(); ++i) {
    const json& c = a["point"][i];
    if (!c.is_number() || !std::isfinite(c.get<double>()))
      throw std::invalid_argument(w + "/away_from/point/" + std::to_string(i) + ": expected a finite number, found " +
                                  c.dump().substr(0, 80));
    e.point.push_back(c.get<double>());
    if (has_every(e.fields[i]) != has_every(e.fields[0]))
      throw std::invalid_argument(w + "/field: " + e.fields[i].text + ": every field with [*], or none");
  }
  e.within = a["beyond"].get<double>();
  std::string f_text, p_text;
  for (std::size_t i = 0; i < e.fields.size(); ++i) {
    f_text += (i ? ", " : "") + e.fields[i].text;
    p_text += (i ? ", " : "") + num(e.point[i]);
  }
  e.text = "(" + f_text + ") at least " + num(e.within) + " from (" + p_text + ")";
}

void parse_near(const json& x, Expectation& e, const std::vector<std::string>& kinds, const cdr::CdrJson* ref_idl,
                const std::string& ref_type) {
  const std::string& w = e.where;
  need_numbers(e, kinds, "near");
  e.test = Expectation::Test::near;
  const json& n = x["near"];
  if (!ref_idl) throw std::invalid_argument(w + "/near: compares with the input 'ref', which is not wired");
  if (!n.is_object() || !n.contains("field") || !n.contains("within") || n.size() != 2 || !n["within"].is_number() ||
      !(n["within"].get<double>() >= 0))
    throw std::invalid_argument(w + "/near: expected {\"field\": PATH or [PATH, ...], \"within\": DISTANCE >= 0}");
  std::vector<std::string> ref_kinds;
  e.ref_fields = paths(n["field"], w + "/near/field", *ref_idl, ref_type, true, &ref_kinds);
  for (std::size_t i = 0; i < ref_kinds.size(); ++i)
    if (ref_kinds[i] != "number")
      throw std::invalid_argument(w + "/near/field: " + e.ref_fields[i].text + " is a " + ref_kinds[i] + ", not a number");
  if (e.ref_fields.size() != e.fields.size())
    throw std::invalid_argument(w + "/near/field: " + std::to_string(e.ref_fields.size()) + " fields against " +
                                std::to_string(e.fields.size()));
  for (const auto* list : {&e.fields, &e.ref_fields})
    for (const auto& p : *list)
      if (has_every(p)) throw std::invalid_argument(w + "/near: " + p.text + ": one value each, no [*]");
  e.within = n["within"].get<double>();
  std::string a, b;
  for (const auto& p : e.fields) a += (a.empty() ? "" : ", ") + p.text;
  for (const auto& p : e.ref_fields) b += (b.empty() ? "" : ", ") + p.text;
  e.text = "(" + a + ") within " + num(e.within) + " of ref's (" + b + ")";
}

// A field's expectation: its field (or fields) and exactly one test.
void parse_field_check(const json& x, Expectation& e, const cdr::CdrJson& idl, const std::string& type, const cdr::CdrJson* ref_idl,
                       const std::string& ref_type) {
  const std::string& w = e.where;
  if (!x.contains("field")) throw std::invalid_argument(w + ": needs field (or count, rate_hz, age_s)");
  int tests = 0;
  for (const char* t : {"range", "equals", "values", "increasing", "nondecreasing", "decreasing", "nonincreasing", "near", "away_from"})
    tests += x.contains(t);
  if (tests != 1)
    throw std::invalid_argument(w + ": needs exactly one of range, equals, values, increasing, nondecreasing, decreasing, nonincreasing, "
                                    "near, away_from");
  std::vector<std::string> kinds;
  e.fields = paths(x["field"], w + "/field", idl, type, x.contains("near") || x.contains("away_from"), &kinds);
  if (x.contains("range")) {
    need_numbers(e, kinds, "range");
    e.test = Expectation::Test::range;
    std::tie(e.lo, e.hi) = pair_of(x["range"], w + "/range");
    e.text = e.fields[0].text + " within [" + num(e.lo) + ", " + num(e.hi) + "]";
  } else if (x.contains("equals")) {
    parse_equals(x, e, kinds);
  } else if (x.contains("values")) {
    parse_values(x, e, kinds);
  } else if (x.contains("increasing") || x.contains("nondecreasing") || x.contains("decreasing") || x.contains("nonincreasing")) {
    parse_monotonic(x, e, kinds);
  } else if (x.contains("away_from")) {
    parse_away_from(x, e, kinds);
  } else {
    parse_near(x, e, kinds, ref_idl, ref_type);
  }
}

// always or eventually, over the whole run or a window; always over the whole run when neither.
void parse_when(const json& x, Expectation& e) {
  const std::string& w = e.where;
  if (x.contains("always") && x.contains("eventually")) throw std::invalid_argument(w + ": always or eventually, not both");
  for (const char* key : {"always", "eventually"}) {
    if (!x.contains(key)) continue;
    e.when = std::string(key) == "always" ? Expectation::When::always : Expectation::When::eventually;
    if (x[key] != true) std::tie(e.from_s, e.to_s) = pair_of(x[key], w + "/" + key);
  }
  e.text += std::string(e.when == Expectation::When::always ? ", always in " : ", eventually in ") + window_text(e.from_s, e.to_s);
}

}  // namespace

std::vector<Expectation> parse_expectations(const json& spec, const cdr::CdrJson& idl, const std::string& type,
                                            const cdr::CdrJson* ref_idl, const std::string& ref_type) {
  check_spec_list(spec);
  std::vector<Expectation> out;
  for (std::size_t k = 0; k < spec.size(); ++k) {
    const json& x = spec[k];
    Expectation e;
    e.where = "/" + std::to_string(k);
    check_known_keys(x, e.where);
    if (x.contains("count") || x.contains("rate_hz") || x.contains("age_s")) {
      parse_stream_check(x, e, idl, type);
    } else {
      parse_field_check(x, e, idl, type, ref_idl, ref_type);
      parse_when(x, e);
    }
    out.push_back(std::move(e));
  }
  return out;
}

ExpectationChecker::ExpectationChecker(std::vector<Expectation> e) : e_(std::move(e)), state_(e_.size()) {}

void ExpectationChecker::feed(double t_s, const unsigned char* bytes, std::size_t size) {
  auto add = [&](const unsigned char* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) hash_ = (hash_ ^ p[i]) * 1099511628211ull;
  };
  add(reinterpret_cast<const unsigned char*>(&t_s), sizeof t_s);
  add(bytes, size);
}

std::string ExpectationChecker::digest() const {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(hash_));
  return b;
}

void ExpectationChecker::observe(double t_s, const json& sample) {
  if (samples_ == 0) first_s_ = t_s;
  last_s_ = t_s;
  const std::uint64_t index = samples_++;
  observe_ages(t_s, index, sample);
  for (std::size_t i = 0; i < e_.size(); ++i) {
    const Expectation& e = e_[i];
    State& st = state_[i];
    if (e.kind != Expectation::Kind::field || t_s < e.from_s - 1e-9 || t_s > e.to_s + 1e-9) continue;
    if (e.test == Expectation::Test::near && !ref_) continue;  // nothing to compare with yet
    ++st.in_window;
    values_.clear();
    const std::string bad = e.test == Expectation::Test::near        ? near_failure(e, sample)
                            : e.test == Expectation::Test::away_from ? away_from_failure(e, sample)
                                                                     : value_failure(e, st, sample);
    char at[96];
    std::snprintf(at, sizeof at, "sample %llu at %.3f s", static_cast<unsigned long long>(index), t_s);
    if (bad.empty()) {
      st.held = true;  // eventually: it held here
    } else {
      if (st.failed++ == 0) st.first_failure = std::string(at) + ": " + bad;
      st.last_seen = std::string(at) + ": " + bad;
    }
  }
}

// Ages: the arrival less the sample's own stamp.
void ExpectationChecker::observe_ages(double t_s, std::uint64_t index, const json& sample) {
  for (std::size_t i = 0; i < e_.size(); ++i) {
    const Expectation& e = e_[i];
    if (e.kind != Expectation::Kind::age) continue;
    State& st = state_[i];
    ++st.in_window;
    const json* stamp = sample.contains("header") ? &sample["header"] : nullptr;
    stamp = stamp && stamp->is_object() && stamp->contains("stamp_ns") ? &(*stamp)["stamp_ns"] : nullptr;
    if (!stamp || !stamp->is_number()) continue;
    ++checks_;
    const double age = t_s - stamp->get<double>() * 1e-9;
    if (age >= e.lo - 1e-9 && age <= e.hi + 1e-9) continue;
    char at[160];
    std::snprintf(at, sizeof at, "sample %llu at %.6f s stamped %.6f s: %.6f s old", static_cast<unsigned long long>(index), t_s,
                  stamp->get<double>() * 1e-9, age);
    if (st.failed++ == 0) st.first_failure = at;
  }
}

std::string ExpectationChecker::near_failure(const Expectation& e, const json& sample) {
  std::string bad, missing;
  double distance = 0;
  for (std::size_t f = 0; f < e.fields.size() && bad.empty(); ++f) {
    values_.clear();
    ref_values_.clear();
    std::string ref_missing;
    cdr::field_values(sample, e.fields[f], values_, missing);
    cdr::field_values(*ref_, e.ref_fields[f], ref_values_, ref_missing);
    if (!missing.empty()) bad = "it has no " + missing;
    else if (!ref_missing.empty()) bad = "ref's sample has no " + ref_missing;
    else {
      const double d = values_[0].value->get<double>() - ref_values_[0].value->get<double>();
      distance += d * d;
    }
    ++checks_;
  }
  distance = std::sqrt(distance);
  if (bad.empty() && !(distance <= e.within)) bad = "distance " + num(distance);
  return bad;
}

std::string ExpectationChecker::away_from_failure(const Expectation& e, const json& sample) {
  std::string bad, missing;
  point_values_.resize(e.fields.size());
  for (std::size_t f = 0; f < e.fields.size(); ++f) {
    point_values_[f].clear();
    cdr::field_values(sample, e.fields[f], point_values_[f], missing);
  }
  const std::size_t n = point_values_[0].size();
  if (!missing.empty()) bad = "it has no " + missing;
  for (std::size_t f = 1; f < e.fields.size() && bad.empty(); ++f)
    if (point_values_[f].size() != n)
      bad = e.fields[f].text + " has " + std::to_string(point_values_[f].size()) + " values against " + std::to_string(n) + " of " +
            e.fields[0].text;
  for (std::size_t i = 0; i < n && bad.empty(); ++i) {
    ++checks_;
    double d2 = 0;
    for (std::size_t f = 0; f < e.fields.size(); ++f) {
      const double d = point_values_[f][i].value->get<double>() - e.point[f];
      d2 += d * d;
    }
    if (!(std::sqrt(d2) >= e.within)) {
      std::string at;
      for (std::size_t f = 0; f < e.fields.size(); ++f)
        at += (f ? ", " : "") + cdr::concrete(e.fields[f], point_values_[f][i].every) + " = " + show(*point_values_[f][i].value);
      bad = at + ": " + num(std::sqrt(d2)) + " from it";
    }
  }
  return bad;
}

std::string ExpectationChecker::value_failure(const Expectation& e, State& st, const json& sample) {
  std::string bad, missing;
  cdr::field_values(sample, e.fields[0], values_, missing);
  if (!missing.empty()) bad = "it has no " + missing;
  const bool along = has_every(e.fields[0]);
  std::optional<double> prev = along ? std::nullopt : st.previous;
  for (const auto& fv : values_) {
    ++checks_;
    const json& v = *fv.value;
    bool ok = true;
    switch (e.test) {
      case Expectation::Test::range: {
        const double d = v.get<double>();
        ok = d >= e.lo && d <= e.hi;
        break;
      }
      case Expectation::Test::equals:
        ok = v.is_number() ? std::abs(v.get<double>() - e.equals.get<double>()) <= e.tolerance : v == e.equals;
        break;
      case Expectation::Test::values: {  // the k-th sample in the window, against the k-th value
        const std::uint64_t k = st.in_window - 1;
        if (k >= e.equals.size()) break;
        const json& want = e.equals[k];
        ok = v.is_number() ? std::abs(v.get<double>() - want.get<double>()) <= e.tolerance : v == want;
        if (!ok) bad = cdr::concrete(e.fields[0], fv.every) + " = " + show(v) + ", expected " + show(want);
        break;
      }
      default: {  // increasing, nondecreasing, decreasing, nonincreasing
        const double d = v.get<double>();
        if (prev)
          ok = e.test == Expectation::Test::increasing      ? d > *prev
               : e.test == Expectation::Test::nondecreasing ? d >= *prev
               : e.test == Expectation::Test::decreasing    ? d < *prev
                                                            : d <= *prev;
        if (!ok && bad.empty()) bad = cdr::concrete(e.fields[0], fv.every) + " = " + show(v) + " after " + num(*prev);
        prev = d;
        if (!along) st.previous = d;
      }
    }
    if (!ok && bad.empty()) bad = cdr::concrete(e.fields[0], fv.every) + " = " + show(v);
  }
  return bad;
}

std::vector<std::string> ExpectationChecker::finish() const {
  std::vector<std::string> out;
  const double rate = samples_ > 1 && last_s_ > first_s_ ? static_cast<double>(samples_ - 1) / (last_s_ - first_s_) : 0.0;
  for (std::size_t i = 0; i < e_.size(); ++i) {
    const Expectation& e = e_[i];
    const State& st = state_[i];
    const std::string head = e.where + " " + e.text + ": ";
    if (e.kind == Expectation::Kind::count) {
      const double n = static_cast<double>(samples_);
      if (n < e.lo || n > e.hi) out.push_back(head + std::to_string(samples_) + " samples");
    } else if (e.kind == Expectation::Kind::rate) {
      if (rate < e.lo || rate > e.hi) out.push_back(head + num(rate) + " Hz over " + std::to_string(samples_) + " samples");
    } else if (e.kind == Expectation::Kind::age) {
      if (st.failed > 0)
        out.push_back(head + st.first_failure + (st.failed > 1 ? " (" + std::to_string(st.failed) + " of " + std::to_string(st.in_window) + " samples)" : ""));
    } else if (e.test == Expectation::Test::values && st.in_window < e.equals.size() && st.failed == 0) {
      out.push_back(head + "only " + std::to_string(st.in_window) + " samples");
    } else if (st.in_window == 0) {
      out.push_back(head + "no sample in " + window_text(e.from_s, e.to_s) +
                    (e.test == Expectation::Test::near && !ref_ ? " (none from ref)" : ""));
    } else if (e.when == Expectation::When::always && st.failed > 0) {
      out.push_back(head + st.first_failure +
                    (st.failed > 1 ? " (" + std::to_string(st.failed) + " of " + std::to_string(st.in_window) + " samples failed)" : ""));
    } else if (e.when == Expectation::When::eventually && !st.held) {
      out.push_back(head + "never held over " + std::to_string(st.in_window) + " samples; the last, " + st.last_seen);
    }
  }
  return out;
}

}  // namespace brickyard::testing
