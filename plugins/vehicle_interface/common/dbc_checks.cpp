#include "dbc_checks.hpp"

#include "can_frame.hpp"
#include "can_signal.hpp"

#include <bitset>
#include <cmath>
#include <map>

namespace brickyard::vehicle_interface {

namespace {

using PayloadBits = std::bitset<kFdMaxBytes * 8>;

PayloadBits bits_of(const DbcSignal& s) {
  PayloadBits bits;
  for (uint32_t j = 0; j < s.length; ++j) {
    const BitLocation at = locate_raw_bit(s, j);
    bits.set(at.byte * 8 + at.bit);
  }
  return bits;
}

bool may_share_frame(const DbcSignal& a, const DbcSignal& b) {
  return !a.multiplexer_value || !b.multiplexer_value || *a.multiplexer_value == *b.multiplexer_value;
}

// The first signal before `index` that shares a bit with it in a frame: named only for an error.
const DbcSignal* first_overlap(const DbcMessage& m, size_t index) {
  const PayloadBits bits = bits_of(m.signals[index]);
  for (size_t i = 0; i < index; ++i) {
    const DbcSignal& other = m.signals[i];
    if (signal_fits(other, m.length) && may_share_frame(other, m.signals[index]) && (bits_of(other) & bits).any())
      return &other;
  }
  return nullptr;
}

}  // namespace

std::string signal_problem(const DbcSignal& s, const DbcMessage& m) {
  if (s.length == 0 || s.length > 64) return "length " + std::to_string(s.length) + " (1 to 64 bits)";
  if (!std::isfinite(s.factor) || s.factor == 0) return "factor must be a non-zero number";
  if (!std::isfinite(s.offset)) return "offset must be a number";
  if (!std::isfinite(s.minimum) || !std::isfinite(s.maximum) || s.minimum > s.maximum)
    return "range [min|max] must be two numbers, min <= max";
  if (!raw_range(s)) return "range [min|max] lies outside what its " + std::to_string(s.length) + " bits carry";
  if (!m.independent_signals && !signal_fits(s, m.length))
    return "bits outside the message's " + std::to_string(m.length) + " bytes";
  return "";
}

std::string value_type_problem(const DbcSignal& s) {
  if (s.value_type == SignalValueType::kFloat32 && s.length != 32) return "a float (SIG_VALTYPE_ 1) needs 32 bits";
  if (s.value_type == SignalValueType::kFloat64 && s.length != 64) return "a double (SIG_VALTYPE_ 2) needs 64 bits";
  return "";
}

// One pass: the bits of the unmultiplexed signals, of every multiplexed one and of each
// multiplexer value's; a signal clashes with the unmultiplexed bits, and with all multiplexed
// bits when it is not multiplexed itself, or its own value's when it is.
std::vector<LayoutProblem> message_layout_problems(const DbcMessage& m) {
  std::vector<LayoutProblem> problems;
  if (m.independent_signals || m.extended_multiplexing) return problems;
  PayloadBits plain, all_multiplexed;
  std::map<uint64_t, PayloadBits> by_value;
  bool has_multiplexer = false;
  for (size_t i = 0; i < m.signals.size(); ++i) {
    const DbcSignal& s = m.signals[i];
    if (!signal_fits(s, m.length)) continue;  // reported by signal_problem
    has_multiplexer = has_multiplexer || s.is_multiplexer;
    const PayloadBits bits = bits_of(s);
    const PayloadBits taken = s.multiplexer_value ? plain | by_value[*s.multiplexer_value] : plain | all_multiplexed;
    if ((bits & taken).any()) {
      const DbcSignal* other = first_overlap(m, i);
      problems.push_back({s.line, "signal " + s.name + ": shares bits with " + (other ? other->name : "another signal")});
    }
    if (s.multiplexer_value) {
      by_value[*s.multiplexer_value] |= bits;
      all_multiplexed |= bits;
    } else {
      plain |= bits;
    }
  }
  for (const DbcSignal& s : m.signals)
    if (s.multiplexer_value && !has_multiplexer)
      problems.push_back({s.line, "signal " + s.name + ": multiplexed, but message " + m.name + " has no multiplexer (M)"});
  return problems;
}

}  // namespace brickyard::vehicle_interface
