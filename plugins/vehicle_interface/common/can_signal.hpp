#pragma once
// One DBC signal in a payload: where its bits lie (Intel or Motorola order), raw bits to the
// physical value and back (rounded, clamped to what the signal can carry, the clamping reported),
// and the check of a value against the signal's declared [min|max]. docs/can-dbc.md, "Conventions".
#include "dbc.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>

namespace brickyard::vehicle_interface {

// Every bit of the signal lies inside a payload of `payload_bytes` bytes.
bool signal_fits(const DbcSignal& signal, size_t payload_bytes);

// Payload byte and bit (0 = least significant) of the signal's raw bit `raw_bit` (0 = its least
// significant). Intel: raw bit j is DBC bit start + j. Motorola: the start bit is the most
// significant bit; going down in significance walks each byte from bit 7 to bit 0, then to bit 7
// of the next byte (DBC's "sawtooth" numbering).
struct BitLocation {
  uint64_t byte = 0;
  uint32_t bit = 0;
};
BitLocation locate_raw_bit(const DbcSignal& signal, uint32_t raw_bit);

// The signal's raw bits (its `length` low bits), read from or written into a payload that
// signal_fits() (the caller checks). Writing changes only the signal's bits.
uint64_t read_raw(const DbcSignal& signal, const uint8_t* payload);
void write_raw(const DbcSignal& signal, uint64_t raw, uint8_t* payload);

// raw * factor + offset, the raw bits read as the signal's type (two's complement when signed,
// an IEEE float for SIG_VALTYPE_ 1 and 2).
double raw_to_physical(const DbcSignal& signal, uint64_t raw);

// The raw integers an integer signal may carry: what its bits hold, narrowed to its declared
// [min|max] when it has one. Empty when they do not meet (a range its bits cannot carry).
struct RawRange {
  double lowest = 0;
  double highest = 0;
};
std::optional<RawRange> raw_range(const DbcSignal& signal);

struct RawValue {
  uint64_t raw = 0;
  bool clamped = false;  // the value lay outside what the signal carries: the nearest end was written
};
// (physical - offset) / factor rounded to the nearest raw value (halves away from zero) and
// clamped to raw_range(); float signals clamp to [min|max] only. No value for NaN or infinity.
std::optional<RawValue> physical_to_raw(const DbcSignal& signal, double physical);

enum class RangeCheck { kInside, kBelowMinimum, kAboveMaximum, kNotANumber };
// Against the declared [min|max] (a millionth of a raw step of slack for rounding); a signal
// without a declared range takes every number. NaN (a float signal's bits can hold one) is never inside.
RangeCheck check_range(const DbcSignal& signal, double physical);

}  // namespace brickyard::vehicle_interface
