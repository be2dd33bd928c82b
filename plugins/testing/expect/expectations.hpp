#pragma once
// What testing.expect checks on a stream of any message type, decoded by its IDL: each
// expectation a field (by path), a predicate and a time window, or the stream's count or rate;
// every failed one reported at the end, each with its field, sample and time
// (docs/testing.md). Framework-free: unit tests feed it decoded samples directly.
#include "cdr/cdr_json.hpp"
#include "cdr/field_path.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::testing {

struct Expectation {
  enum class Kind { count, rate, age, field } kind = Kind::field;
  enum class Test { range, equals, values, increasing, nondecreasing, decreasing, nonincreasing, near, away_from } test = Test::range;
  enum class When { always, eventually } when = When::always;
  std::string where;                     // "/3": its place in the parameter
  std::string text;                      // what it asks, as said in a report
  std::vector<cdr::FieldPath> fields;    // one; several (a point) for near and away_from
  std::vector<cdr::FieldPath> ref_fields;
  double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
  nlohmann::json equals;                 // equals: the value; values: the list
  std::vector<double> point;             // away_from: the point every one of the fields' points keeps clear of
  double tolerance = 0, within = 0;      // within: near's distance, away_from's least one
  double from_s = -std::numeric_limits<double>::infinity(), to_s = std::numeric_limits<double>::infinity();
};

// Reads the "expect" parameter, each path checked against the types: throws std::invalid_argument
// "/2/field: poses[0].q: no member 'q' in Pose2D (members: x, y, yaw)". `ref` null: no ref wired.
std::vector<Expectation> parse_expectations(const nlohmann::json& spec, const cdr::CdrJson& idl, const std::string& type,
                                            const cdr::CdrJson* ref_idl, const std::string& ref_type);

class ExpectationChecker {
 public:
  explicit ExpectationChecker(std::vector<Expectation> e);
  // The newest sample of the reference wire (for near): kept until the next.
  void reference(const nlohmann::json& sample) { ref_ = sample; }
  // One sample of the stream under test, at t_s on the run's clock.
  void observe(double t_s, const nlohmann::json& sample);
  // A digest of every sample's time and bytes (FNV-1a), for determinism tests: feed() each one.
  void feed(double t_s, const unsigned char* bytes, std::size_t size);
  std::string digest() const;
  // Every expectation that failed, in order, each one line: "/2 poses[*].x within [0, 100]:
  // sample 17 at 3.250 s: poses[4].x = 101.2 (and 3 more samples)".
  std::vector<std::string> finish() const;

  std::uint64_t samples() const { return samples_; }
  std::uint64_t field_checks() const { return checks_; }
  std::size_t size() const { return e_.size(); }

 private:
  struct State {
    std::uint64_t in_window = 0, failed = 0;
    bool held = false;
    std::string first_failure, last_seen;
    std::optional<double> previous;
  };
  void observe_ages(double t_s, std::uint64_t index, const nlohmann::json& sample);
  // A field expectation's check of one sample: its first failing value, said as "path = value"
  // (or what is missing); empty when it held.
  std::string near_failure(const Expectation& e, const nlohmann::json& sample);
  std::string away_from_failure(const Expectation& e, const nlohmann::json& sample);
  std::string value_failure(const Expectation& e, State& st, const nlohmann::json& sample);
  std::vector<Expectation> e_;
  std::vector<State> state_;
  std::optional<nlohmann::json> ref_;
  std::uint64_t samples_ = 0, checks_ = 0, hash_ = 1469598103934665603ull;
  double first_s_ = 0, last_s_ = 0;
  std::vector<cdr::FieldValue> values_, ref_values_;
  std::vector<std::vector<cdr::FieldValue>> point_values_;  // away_from: each field's values
};

}  // namespace brickyard::testing
