#include "raptor_dbc.hpp"

#include "can_signal.hpp"

#include <cmath>

namespace brickyard::vehicle_interface {

namespace {

// The signal names are the DBC's (data/vehicle_interface/CAN1-INDY-V14.dbc), spelt as it spells them.
const std::array<RaptorMessageSpec, kRaptorMessageCount>& specs() {
  static const std::array<RaptorMessageSpec, kRaptorMessageCount> table = {{
      {"brake_pressure_cmd", "brk_pressure_cmd_counter", {"brake_pressure_cmd"}},
      {"accelerator_cmd", "acc_pedal_cmd_counter", {"acc_pedal_cmd"}},
      {"steering_cmd", "steering_motor_cmd_counter", {"steering_motor_ang_cmd"}},
      {"gear_shift_cmd", nullptr, {"desired_gear"}},
      {"ct_report", "ct_state_rolling_counter", {"ct_state", "veh_num", "track_cond_ack", "veh_sig_ack"}},
      {"wheel_speed_report", nullptr, {"wheel_speed_FL", "wheel_speed_FR", "wheel_speed_RL", "wheel_speed_RR"}},
      {"brake_pressure_report", "brk_pressure_fdbk_counter", {"brake_pressure_fdbk_front", "brake_pressure_fdbk_rear"}},
      {"accelerator_report", "acc_pedal_fdbk_counter", {"acc_pedal_fdbk"}},
      {"steering_report", "steering_motor_fdbk_counter", {"steering_motor_ang_avg_fdbk"}},
      {"pt_report_1", nullptr,
       {"throttle_position", "current_gear", "engine_speed_rpm", "vehicle_speed_kmph", "engine_run_switch", "engine_state",
        "gear_shift_status"}},
      {"diagnostic_report", nullptr, {}},  // its signals: raptor_diagnostic_bits() and motec_warning
  }};
  return table;
}

std::vector<const char*> needed_signals(RaptorMessage m) {
  std::vector<const char*> names = raptor_spec(m).signals;
  if (m == RaptorMessage::diagnostic_report) {
    names = raptor_diagnostic_bits();
    names.push_back("motec_warning");
  }
  if (const char* c = raptor_spec(m).counter) names.push_back(c);
  return names;
}

std::string all_names() {
  std::string out;
  for (const RaptorMessageSpec& s : specs()) out += (out.empty() ? "" : ", ") + std::string(s.name);
  return out;
}

// "" or why `m` cannot be this message: a signal missing, or a message pack/unpack refuse.
std::string message_problem(const DbcMessage& m, RaptorMessage which, const std::string& file) {
  const std::string at = file + ":" + std::to_string(m.line) + ": message " + m.name;
  if (m.independent_signals || m.extended_multiplexing) return at + ": its signals cannot be packed (extended multiplexing)";
  for (const char* name : needed_signals(which)) {
    const DbcSignal* s = m.find_signal(name);
    if (!s) return at + " has no signal " + name;
    if (s->multiplexer_value) return file + ":" + std::to_string(s->line) + ": signal " + name + " is multiplexed";
    const char* counter = raptor_spec(which).counter;
    if (s->value_type != SignalValueType::kInteger && counter && std::string_view(counter) == name)
      return file + ":" + std::to_string(s->line) + ": counter " + name + " is not an integer";
  }
  return "";
}

}  // namespace

const RaptorMessageSpec& raptor_spec(RaptorMessage m) { return specs()[raptor_index(m)]; }

const std::vector<const char*>& raptor_diagnostic_bits() {
  static const std::vector<const char*> bits = {
      "sd_system_warning", "sd_system_failure", "sd_brake_warning1", "sd_brake_warning2", "sd_brake_warning3",
      "sd_steer_warning1", "sd_steer_warning2", "sd_steer_warning3", "est1_oos_front_brk", "est2_oos_rear_brk",
      "est3_low_eng_speed", "est4_sd_comms_loss", "est5_motec_comms_loss", "est6_sd_ebrake", "adlink_hb_lost", "rc_lost"};
  return bits;
}

uint32_t raptor_diagnostic_mask(std::string_view name) {
  const auto& bits = raptor_diagnostic_bits();
  for (size_t k = 0; k < bits.size(); ++k)
    if (name == bits[k]) return 1u << k;
  return 0;
}

std::optional<RaptorDbc> RaptorDbc::make(const DbcDatabase& db, const std::string& file, std::string& error) {
  RaptorDbc out;
  for (size_t i = 0; i < kRaptorMessageCount; ++i) {
    const auto which = static_cast<RaptorMessage>(i);
    const DbcMessage* m = db.find(raptor_name(which));
    if (!m) {
      error = file + ": no message " + raptor_name(which) + " (the vehicle interface needs " + all_names() + ")";
      return std::nullopt;
    }
    if (std::string why = message_problem(*m, which, file); !why.empty()) {
      error = std::move(why);
      return std::nullopt;
    }
    out.messages_[i] = *m;
    if (const char* c = raptor_spec(which).counter) {
      const std::optional<RawRange> r = raw_range(*m->find_signal(c));
      if (!r || r->lowest != 0 || r->highest < 1 || r->highest > 65535) {
        error = file + ":" + std::to_string(m->find_signal(c)->line) + ": counter " + c + " does not count from 0 (0 to at least 1, at most 65535)";
        return std::nullopt;
      }
      out.moduli_[i] = static_cast<uint32_t>(r->highest) + 1;
    }
  }
  return out;
}

const DbcSignal& RaptorDbc::signal(RaptorMessage m, const char* name) const {
  return *message(m).find_signal(name);  // make() checked that every needed signal is there
}

std::optional<RaptorMessage> RaptorDbc::which(const CanFrame& frame) const {
  for (size_t i = 0; i < kRaptorMessageCount; ++i)
    if (messages_[i].id == frame.id && messages_[i].extended == frame.extended) return static_cast<RaptorMessage>(i);
  return std::nullopt;
}

PackResult RaptorDbc::pack(RaptorMessage m, SignalValues values, uint32_t counter) const {
  if (const char* c = raptor_spec(m).counter) values[c] = static_cast<double>(counter % counter_modulus(m));
  return pack_message(message(m), values);
}

std::optional<RaptorFrame> RaptorDbc::unpack(const CanFrame& frame) const {
  const std::optional<RaptorMessage> m = which(frame);
  if (!m) return std::nullopt;
  UnpackResult u = unpack_message(message(*m), frame);
  RaptorFrame out;
  out.message = *m;
  out.error = std::move(u.error);
  out.out_of_range = std::move(u.out_of_range);
  out.values = std::move(u.values);
  if (const char* c = raptor_spec(*m).counter; c && out.error.empty()) {
    const double v = out.values.at(c);
    if (v >= 0 && v < counter_modulus(*m)) out.counter = static_cast<uint32_t>(v);
    // a counter outside its range is in out_of_range already, and no counter: the frame is not counted as in order
  }
  return out;
}

}  // namespace brickyard::vehicle_interface
