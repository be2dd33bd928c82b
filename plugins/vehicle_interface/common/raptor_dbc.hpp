#pragma once
// The messages of New Eagle's Raptor drive-by-wire that the vehicle interface speaks, found by name
// in the car's DBC (docs/vehicle-interface.md): the five commands the stack sends, the six reports
// it reads. Each is checked once, when the DBC is read: a message or a signal the interface needs
// and the file lacks is an error naming the file, the line and the name, so a run never starts
// on a DBC it cannot speak. Framework-free.
#include "can_message.hpp"
#include "dbc.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::vehicle_interface {

enum class RaptorMessage : uint8_t {
  // commands, team to Raptor
  brake_pressure_cmd,  // 1400
  accelerator_cmd,     // 1401
  steering_cmd,        // 1402
  gear_shift_cmd,      // 1403
  ct_report,           // 1404: the team's state and heartbeat
  // reports, Raptor to team
  wheel_speed_report,     // 1300
  brake_pressure_report,  // 1301
  accelerator_report,     // 1302
  steering_report,        // 1303
  pt_report_1,            // 1340
  diagnostic_report,      // 1342
};
inline constexpr size_t kRaptorMessageCount = 11;
inline constexpr std::array<RaptorMessage, 5> kRaptorCommands = {
    RaptorMessage::brake_pressure_cmd, RaptorMessage::accelerator_cmd, RaptorMessage::steering_cmd,
    RaptorMessage::gear_shift_cmd, RaptorMessage::ct_report};
inline constexpr std::array<RaptorMessage, 6> kRaptorReports = {
    RaptorMessage::wheel_speed_report, RaptorMessage::brake_pressure_report, RaptorMessage::accelerator_report,
    RaptorMessage::steering_report, RaptorMessage::pt_report_1, RaptorMessage::diagnostic_report};

// What the interface needs of one message: its name in the DBC, its rolling counter's signal (none
// for the messages that carry none), and the signals it reads or writes.
struct RaptorMessageSpec {
  const char* name;
  const char* counter;  // nullptr: no counter
  std::vector<const char*> signals;
};
const RaptorMessageSpec& raptor_spec(RaptorMessage m);
inline const char* raptor_name(RaptorMessage m) { return raptor_spec(m).name; }
inline size_t raptor_index(RaptorMessage m) { return static_cast<size_t>(m); }

// diagnostic_report's one-bit signals, in the order of VehicleStatus.diagnostic_bits (bit k = the k-th).
const std::vector<const char*>& raptor_diagnostic_bits();
// The mask of one of them by name (0 for a name that is none).
uint32_t raptor_diagnostic_mask(std::string_view name);

// A frame of one of these messages read back: its values by signal name, its counter's value.
struct RaptorFrame {
  RaptorMessage message{};
  SignalValues values;
  std::optional<uint32_t> counter;        // the message's rolling counter, when it has one
  std::vector<std::string> out_of_range;  // signals outside their declared [min|max]
  std::string error;                      // non-empty: the frame could not be read (too short, ...)
};

class RaptorDbc {
 public:
  // The messages found in `db`, or nullopt and `error` naming `file`, the line and what is missing
  // ("CAN1.dbc: no message steering_cmd (needed: ...)", "CAN1.dbc:312: message steering_cmd has no
  // signal steering_motor_cmd_counter").
  static std::optional<RaptorDbc> make(const DbcDatabase& db, const std::string& file, std::string& error);

  const DbcMessage& message(RaptorMessage m) const { return messages_[raptor_index(m)]; }
  const DbcSignal& signal(RaptorMessage m, const char* name) const;
  // The counter's values run 0 .. modulus - 1 (the raw values its signal carries, narrowed to its
  // declared range: 256 for an 8-bit counter, 10 for ct_report's [0|9]); 0 when it has no counter.
  uint32_t counter_modulus(RaptorMessage m) const { return moduli_[raptor_index(m)]; }
  // Which of the messages a frame is (by id and format), if any.
  std::optional<RaptorMessage> which(const CanFrame& frame) const;

  // Packs the values and, when the message has one, the counter (taken modulo its modulus).
  PackResult pack(RaptorMessage m, SignalValues values, uint32_t counter = 0) const;
  // Unpacks a frame of one of the messages (nullopt: none of them).
  std::optional<RaptorFrame> unpack(const CanFrame& frame) const;

 private:
  std::array<DbcMessage, kRaptorMessageCount> messages_;
  std::array<uint32_t, kRaptorMessageCount> moduli_{};
};

}  // namespace brickyard::vehicle_interface
