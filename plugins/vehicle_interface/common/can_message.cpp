#include "can_message.hpp"

#include "can_signal.hpp"

#include <cmath>

namespace brickyard::vehicle_interface {

namespace {

// parse_dbc refuses signals outside their message; a message built by hand is checked here too,
// so no signal reads or writes past the payload.
std::string unsupported(const DbcMessage& m) {
  if (m.independent_signals) return "message " + m.name + " holds signals no frame carries";
  if (m.extended_multiplexing) return "message " + m.name + " uses extended multiplexing, which is not supported";
  if (m.length > kFdMaxBytes) return "message " + m.name + ": longer than 64 bytes";
  for (const DbcSignal& s : m.signals)
    if (!signal_fits(s, m.length)) return "signal " + s.name + ": bits outside message " + m.name;
  return "";
}

const DbcSignal* multiplexer_of(const DbcMessage& m) {
  for (const DbcSignal& s : m.signals)
    if (s.is_multiplexer) return &s;
  return nullptr;
}

bool selected(const DbcSignal& s, std::optional<uint64_t> multiplexer_raw) {
  return !s.multiplexer_value || (multiplexer_raw && *s.multiplexer_value == *multiplexer_raw);
}

// Every name known, every value a number, every multiplexed signal selected by the multiplexer's
// value (given, or 0 raw): "" or what is wrong. `multiplexer_raw` gets the multiplexer's raw value.
std::string check_values(const DbcMessage& m, const SignalValues& values, std::optional<uint64_t>& multiplexer_raw) {
  for (const auto& [name, value] : values) {
    if (!m.find_signal(name)) return "message " + m.name + " has no signal " + name;
    if (!std::isfinite(value)) return "signal " + name + ": value is not a finite number";
  }
  if (const DbcSignal* mux = multiplexer_of(m)) {
    const auto given = values.find(mux->name);
    const std::optional<RawValue> raw = given == values.end() ? RawValue{} : physical_to_raw(*mux, given->second);
    if (!raw) return "signal " + mux->name + ": value cannot be encoded";
    multiplexer_raw = raw->raw;
  }
  for (const auto& [name, value] : values) {
    const DbcSignal& s = *m.find_signal(name);
    if (!selected(s, multiplexer_raw))
      return "signal " + name + " is present when the multiplexer reads " + std::to_string(*s.multiplexer_value) +
             ", not " + std::to_string(multiplexer_raw.value_or(0));
  }
  return "";
}

}  // namespace

PackResult pack_message(const DbcMessage& m, const SignalValues& values) {
  PackResult result;
  result.error = unsupported(m);
  std::optional<uint64_t> multiplexer_raw;
  if (result.ok()) result.error = check_values(m, values, multiplexer_raw);
  if (!result.ok()) return result;
  CanFrame& frame = result.frame;
  frame.id = m.id;
  frame.extended = m.extended;
  frame.length = static_cast<uint8_t>(m.length);
  frame.fd = m.length > kClassicMaxBytes;
  for (const DbcSignal& s : m.signals) {
    const auto given = values.find(s.name);
    if (given == values.end() || !selected(s, multiplexer_raw)) continue;  // 0 raw: the payload starts zeroed
    if (check_range(s, given->second) != RangeCheck::kInside) result.out_of_range.push_back(s.name);
    const std::optional<RawValue> raw = physical_to_raw(s, given->second);
    if (!raw) {
      result = PackResult{};
      result.error = "signal " + s.name + ": value cannot be encoded";
      return result;
    }
    if (raw->clamped) result.clamped.push_back(s.name);
    write_raw(s, raw->raw, frame.data.data());
  }
  return result;
}

UnpackResult unpack_message(const DbcMessage& m, const CanFrame& frame) {
  UnpackResult result;
  result.error = unsupported(m);
  if (!result.ok()) return result;
  if (frame.id != m.id || frame.extended != m.extended) {
    result.error = "frame " + std::to_string(frame.id) + (frame.extended ? " (extended)" : "") + " is not message " + m.name;
    return result;
  }
  if (frame.remote) {
    result.error = "frame for message " + m.name + " is a remote request: no data";
    return result;
  }
  if (frame.length < m.length) {
    result.error = "frame of " + std::to_string(frame.length) + " bytes, message " + m.name + " has " + std::to_string(m.length);
    return result;
  }
  std::optional<uint64_t> multiplexer_raw;
  if (const DbcSignal* mux = multiplexer_of(m)) multiplexer_raw = read_raw(*mux, frame.data.data());
  for (const DbcSignal& s : m.signals) {
    if (!selected(s, multiplexer_raw)) continue;
    const double value = raw_to_physical(s, read_raw(s, frame.data.data()));
    if (check_range(s, value) != RangeCheck::kInside) result.out_of_range.push_back(s.name);
    result.values.emplace(s.name, value);
  }
  return result;
}

}  // namespace brickyard::vehicle_interface
