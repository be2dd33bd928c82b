#pragma once
// A CAN database (DBC file) as the car's drive-by-wire publishes it, read without the framework:
// messages (BO_), their signals (SG_), value names (VAL_), comments (CM_) and IEEE-float signal
// types (SIG_VALTYPE_). Everything else the format carries (attributes, nodes' relations, signal
// groups, environment variables) is skipped. Reading never throws on bad text: every problem
// comes back as an error naming the file, the line and what is wrong. docs/can-dbc.md.
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::vehicle_interface {

enum class ByteOrder { kIntel, kMotorola };  // DBC's "@1" (little endian) and "@0" (big endian)
enum class SignalValueType { kInteger, kFloat32, kFloat64 };  // SIG_VALTYPE_ 0, 1, 2

struct DbcSignal {
  std::string name;
  // Intel: the least significant bit's position; Motorola: the most significant bit's. Both in
  // DBC's numbering, byte * 8 + bit, bit 0 the least significant bit of its byte.
  uint32_t start_bit = 0;
  uint32_t length = 0;  // bits, 1..64
  ByteOrder byte_order = ByteOrder::kIntel;
  bool is_signed = false;
  SignalValueType value_type = SignalValueType::kInteger;
  double factor = 1.0;  // physical = raw * factor + offset
  double offset = 0.0;
  double minimum = 0.0;  // [0|0] in the file: no range declared (has_range() false)
  double maximum = 0.0;
  std::string unit;
  std::vector<std::string> receivers;
  bool is_multiplexer = false;                 // "M"
  std::optional<uint64_t> multiplexer_value;   // "m3": present only when the multiplexer reads 3
  std::map<int64_t, std::string> value_names;  // VAL_: raw value -> name
  std::string comment;
  int line = 0;

  bool has_range() const { return minimum != 0.0 || maximum != 0.0; }
};

struct DbcMessage {
  uint32_t id = 0;  // without the extended flag (bit 31 in the file)
  bool extended = false;
  std::string name;
  uint32_t length = 0;  // bytes: 0..8, or a CAN FD length up to 64
  std::string transmitter;
  std::vector<DbcSignal> signals;
  std::string comment;
  int line = 0;
  // Vector's VECTOR__INDEPENDENT_SIG_MSG: a holder for signals no message carries, never on a bus
  // (its id, 0xC0000000, is no CAN id; its length is 0; its signals overlap). Kept, not packed.
  bool independent_signals = false;
  // More than one multiplexer, a signal both multiplexed and a multiplexer ("m1M"), or
  // SG_MUL_VAL_: extended multiplexing, which pack and unpack refuse.
  bool extended_multiplexing = false;

  const DbcSignal* find_signal(std::string_view signal_name) const;
};

struct DbcDatabase {
  std::string version;
  std::vector<std::string> nodes;
  std::vector<DbcMessage> messages;

  const DbcMessage* find(uint32_t id, bool extended) const;
  const DbcMessage* find(std::string_view message_name) const;
  size_t signal_count() const;
};

struct DbcError {
  std::string file;
  int line = 0;  // 1-based; 0 for the file as a whole
  std::string what;

  std::string text() const;  // "CAN1-INDY-V14.dbc:123: signal X: length 0"
};

struct DbcReadResult {
  std::optional<DbcDatabase> database;  // only when there is no error
  std::vector<DbcError> errors;         // at most DbcLimits::max_errors, in line order

  bool ok() const { return database.has_value(); }
};

// Bounds that keep a hostile file's cost in proportion to its size.
struct DbcLimits {
  size_t max_file_bytes = 64u << 20;
  size_t max_errors = 20;
  size_t max_signals_per_message = 2048;  // four times a CAN FD frame's bits: room for multiplexing
};

// `file_name` names the text in errors (the file's name, not a path to open).
DbcReadResult parse_dbc(std::string_view text, std::string_view file_name = "dbc", DbcLimits limits = {});
// Reads `path` (refusing files over the limit) and parses it, errors naming the file's base name.
DbcReadResult load_dbc_file(const std::string& path, DbcLimits limits = {});

}  // namespace brickyard::vehicle_interface
