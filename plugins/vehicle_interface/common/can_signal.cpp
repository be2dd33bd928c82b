#include "can_signal.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace brickyard::vehicle_interface {

namespace {

uint64_t low_mask(uint32_t bits) { return bits >= 64 ? ~uint64_t{0} : (uint64_t{1} << bits) - 1; }

// Big-endian linear index (byte * 8 + 7 - bit) of a Motorola signal's most significant bit: in
// that numbering a Motorola signal's bits are consecutive, most significant first.
uint64_t motorola_msb_index(const DbcSignal& s) { return (s.start_bit / 8) * uint64_t{8} + 7 - s.start_bit % 8; }

// The raw integer limits of an integer signal's bits, as doubles. For 64-bit signals the top
// is the largest double below 2^64 (or 2^63): the nearest one that converts back without overflow.
RawRange bit_range(const DbcSignal& s) {
  if (s.is_signed) {
    if (s.length >= 64) return {-0x1p63, std::nextafter(0x1p63, 0.0)};
    const double half = std::ldexp(1.0, static_cast<int>(s.length) - 1);
    return {-half, half - 1};
  }
  if (s.length >= 64) return {0, std::nextafter(0x1p64, 0.0)};
  return {0, std::ldexp(1.0, static_cast<int>(s.length)) - 1};
}

// Slack for the rounding of (limit - offset) / factor: a millionth of a raw step, plus the
// division's own error on large values.
double raw_slack(double raw) { return 1e-6 + 1e-12 * std::fabs(raw); }

std::optional<RawValue> float_to_raw(const DbcSignal& s, double physical) {
  RawValue out;
  if (s.has_range() && (physical < s.minimum || physical > s.maximum)) {
    physical = std::clamp(physical, s.minimum, s.maximum);
    out.clamped = true;
  }
  double x = (physical - s.offset) / s.factor;
  if (s.value_type == SignalValueType::kFloat32) {
    const double top = std::numeric_limits<float>::max();
    if (std::fabs(x) > top) {
      x = std::clamp(x, -top, top);
      out.clamped = true;
    }
    out.raw = std::bit_cast<uint32_t>(static_cast<float>(x));
  } else {
    if (!std::isfinite(x)) return std::nullopt;
    out.raw = std::bit_cast<uint64_t>(x);
  }
  return out;
}

}  // namespace

bool signal_fits(const DbcSignal& s, size_t payload_bytes) {
  if (s.length == 0 || s.length > 64) return false;
  const uint64_t bits = uint64_t{payload_bytes} * 8;
  if (s.byte_order == ByteOrder::kIntel) return uint64_t{s.start_bit} + s.length <= bits;
  return motorola_msb_index(s) + s.length <= bits;
}

BitLocation locate_raw_bit(const DbcSignal& s, uint32_t raw_bit) {
  if (s.byte_order == ByteOrder::kIntel) {
    const uint64_t at = uint64_t{s.start_bit} + raw_bit;
    return {at / 8, static_cast<uint32_t>(at % 8)};
  }
  const uint64_t be_index = motorola_msb_index(s) + (s.length - 1 - raw_bit);
  return {be_index / 8, static_cast<uint32_t>(7 - be_index % 8)};
}

uint64_t read_raw(const DbcSignal& s, const uint8_t* payload) {
  uint64_t raw = 0;
  for (uint32_t j = 0; j < s.length; ++j) {
    const BitLocation at = locate_raw_bit(s, j);
    raw |= uint64_t{(payload[at.byte] >> at.bit) & 1u} << j;
  }
  return raw;
}

void write_raw(const DbcSignal& s, uint64_t raw, uint8_t* payload) {
  for (uint32_t j = 0; j < s.length; ++j) {
    const BitLocation at = locate_raw_bit(s, j);
    const uint8_t bit = static_cast<uint8_t>(1u << at.bit);
    if ((raw >> j) & 1u)
      payload[at.byte] |= bit;
    else
      payload[at.byte] &= static_cast<uint8_t>(~bit);
  }
}

double raw_to_physical(const DbcSignal& s, uint64_t raw) {
  raw &= low_mask(s.length);
  double value = 0;
  if (s.value_type == SignalValueType::kFloat32) {
    value = std::bit_cast<float>(static_cast<uint32_t>(raw));
  } else if (s.value_type == SignalValueType::kFloat64) {
    value = std::bit_cast<double>(raw);
  } else if (s.is_signed && s.length < 64 && ((raw >> (s.length - 1)) & 1u)) {
    value = static_cast<double>(static_cast<int64_t>(raw | ~low_mask(s.length)));  // sign-extended
  } else if (s.is_signed) {
    value = static_cast<double>(static_cast<int64_t>(raw));
  } else {
    value = static_cast<double>(raw);
  }
  return value * s.factor + s.offset;
}

std::optional<RawRange> raw_range(const DbcSignal& s) {
  RawRange range = bit_range(s);
  if (s.has_range()) {
    double low = (s.minimum - s.offset) / s.factor;
    double high = (s.maximum - s.offset) / s.factor;
    if (s.factor < 0) std::swap(low, high);
    range.lowest = std::max(range.lowest, std::ceil(low - raw_slack(low)));
    range.highest = std::min(range.highest, std::floor(high + raw_slack(high)));
  }
  if (!(range.lowest <= range.highest)) return std::nullopt;
  return range;
}

std::optional<RawValue> physical_to_raw(const DbcSignal& s, double physical) {
  if (!std::isfinite(physical) || s.length == 0 || s.length > 64) return std::nullopt;
  if (s.value_type != SignalValueType::kInteger) return float_to_raw(s, physical);
  const std::optional<RawRange> range = raw_range(s);
  if (!range) return std::nullopt;
  const double wanted = std::round((physical - s.offset) / s.factor);
  RawValue out;
  out.clamped = !(wanted >= range->lowest && wanted <= range->highest);
  const double raw = std::clamp(wanted, range->lowest, range->highest);  // an infinite quotient too
  if (s.is_signed)
    out.raw = static_cast<uint64_t>(static_cast<int64_t>(raw)) & low_mask(s.length);
  else
    out.raw = static_cast<uint64_t>(raw);
  return out;
}

RangeCheck check_range(const DbcSignal& s, double physical) {
  if (std::isnan(physical)) return RangeCheck::kNotANumber;
  if (!s.has_range()) return RangeCheck::kInside;
  const double slack = 1e-6 * std::fabs(s.factor) + 1e-12 * (std::fabs(s.minimum) + std::fabs(s.maximum));
  if (physical < s.minimum - slack) return RangeCheck::kBelowMinimum;
  if (physical > s.maximum + slack) return RangeCheck::kAboveMaximum;
  return RangeCheck::kInside;
}

}  // namespace brickyard::vehicle_interface
