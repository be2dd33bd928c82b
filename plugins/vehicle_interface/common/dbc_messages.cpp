// BO_ and SG_ lines: a message, then its signals, one per line.
//   BO_ 1402 steering_cmd: 8 Vector__XXX
//    SG_ steering_motor_ang_cmd : 0|11@1- (0.5,0) [-1024|1023] "deg" Vector__XXX
#include "can_frame.hpp"
#include "dbc_checks.hpp"
#include "dbc_reader.hpp"

#include <algorithm>

namespace brickyard::vehicle_interface::dbc_detail {

namespace {

constexpr std::string_view kIndependentSignalsMessage = "VECTOR__INDEPENDENT_SIG_MSG";
constexpr uint64_t kMaxStartBit = kFdMaxBytes * 8 - 1;

}  // namespace

bool DbcReader::message() {
  const int line = lex_.take().line;
  skipping_signals_ = true;  // until the message is whole: its SG_ lines would only repeat the error
  DbcMessage m;
  m.line = line;
  const auto file_id = number<uint64_t>("the message id", "an unsigned integer");
  if (!file_id) return false;
  const auto name = expect(DbcTokenKind::kIdentifier, "the message name");
  if (!name) return false;
  m.name = name->text;
  context_ = "message " + m.name + ": ";
  m.independent_signals = m.name == kIndependentSignalsMessage;
  if (!expect_punct(':')) return false;
  const auto length = number<uint64_t>("the message length", "bytes");
  if (!length) return false;
  if (on_same_line()) {
    const auto transmitter = expect(DbcTokenKind::kIdentifier, "the transmitting node");
    if (!transmitter) return false;
    m.transmitter = transmitter->text;
  }
  if (on_same_line()) return fail_at(lex_.peek(), "the end of the line");
  if (!message_id(m, *file_id, line)) return false;
  if (*length > kFdMaxBytes || !is_fd_length(*length))
    return fail(line, "length " + std::to_string(*length) + " is not a CAN (0 to 8) or CAN FD length");
  m.length = static_cast<uint32_t>(*length);
  if (message_index_.count(std::pair(m.id, m.extended)))
    return fail(line, "id " + std::to_string(*file_id) + " given to another message before");
  if (!message_names_.insert(m.name).second) return fail(line, "name given to another message before");
  message_index_.emplace(std::pair(m.id, m.extended), db_.messages.size());  // only for messages kept
  db_.messages.push_back(std::move(m));
  signal_index_.emplace_back();
  open_message_ = db_.messages.size() - 1;
  skipping_signals_ = false;
  return true;
}

// Bit 31 of the file's id flags an extended (29-bit) id; without it the id has 11 bits.
bool DbcReader::message_id(DbcMessage& m, uint64_t file_id, int line) {
  if (file_id > 0xFFFFFFFFu) return fail(line, "id " + std::to_string(file_id) + " over 32 bits");
  m.id = static_cast<uint32_t>(file_id & ~kExtendedIdFlag);
  m.extended = (file_id & kExtendedIdFlag) != 0;
  if (m.independent_signals) return true;  // 0xC0000000 by convention: no CAN id
  if (m.extended && m.id > kExtendedIdMax)
    return fail(line, "extended id " + std::to_string(m.id) + " wider than 29 bits");
  if (!m.extended && m.id > kStandardIdMax)
    return fail(line, "standard id " + std::to_string(m.id) + " over 2047 (an extended id is written with bit 31 set: " +
                          std::to_string(file_id + kExtendedIdFlag) + ")");
  return true;
}

bool DbcReader::signal() {
  const int line = lex_.take().line;
  if (!open_message_) {
    if (skipping_signals_) return skip_to_next_line(), true;
    return fail(line, "signal outside a message (SG_ lines follow their BO_ line)");
  }
  DbcSignal s;
  s.line = line;
  const auto name = expect(DbcTokenKind::kIdentifier, "the signal name");
  if (!name) return false;
  s.name = name->text;
  context_ = "signal " + s.name + ": ";
  if (!signal_multiplexing(s) || !signal_layout(s) || !signal_scaling(s) || !signal_receivers(s)) return false;
  DbcMessage& m = db_.messages[*open_message_];
  if (m.signals.size() >= limits_.max_signals_per_message)
    return fail(line, "more than " + std::to_string(limits_.max_signals_per_message) + " signals in message " + m.name);
  auto& names = signal_index_[*open_message_];
  if (names.count(s.name)) return fail(line, "defined twice in message " + m.name);
  if (const std::string problem = signal_problem(s, m); !problem.empty()) return fail(line, problem);
  if (s.is_multiplexer) {
    const bool second_multiplexer = std::any_of(m.signals.begin(), m.signals.end(), [](const DbcSignal& o) { return o.is_multiplexer; });
    if (s.multiplexer_value || second_multiplexer) m.extended_multiplexing = true;
  }
  names.emplace(s.name, m.signals.size());
  m.signals.push_back(std::move(s));
  return true;
}

// Nothing, "M" (the multiplexer), "m3" (present when the multiplexer reads 3) or "m3M" (both:
// extended multiplexing), then ':'.
bool DbcReader::signal_multiplexing(DbcSignal& s) {
  if (lex_.peek().kind == DbcTokenKind::kIdentifier) {
    const std::string_view mark = lex_.take().text;
    std::string_view digits = mark;
    if (mark == "M") {
      s.is_multiplexer = true;
    } else if (mark.size() >= 2 && mark[0] == 'm') {
      digits = mark.substr(1);
      if (digits.back() == 'M') s.is_multiplexer = true, digits.remove_suffix(1);
      uint64_t value = 0;
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
      if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
        return fail(s.line, "multiplexer mark '" + std::string(mark) + "' is none of M, m<value>, m<value>M");
      s.multiplexer_value = value;
    } else {
      return fail(s.line, "multiplexer mark '" + std::string(mark) + "' is none of M, m<value>, m<value>M");
    }
  }
  return expect_punct(':');
}

// start|length@order sign: "0|11@1-".
bool DbcReader::signal_layout(DbcSignal& s) {
  const auto start = number<uint64_t>("the start bit", "an unsigned integer");
  if (!start || !expect_punct('|')) return false;
  if (*start > kMaxStartBit) return fail(s.line, "start bit " + std::to_string(*start) + " beyond a 64-byte frame");
  s.start_bit = static_cast<uint32_t>(*start);
  const auto length = number<uint64_t>("the length", "bits");
  if (!length || !expect_punct('@')) return false;
  if (*length == 0 || *length > 64) return fail(s.line, "length " + std::to_string(*length) + " (1 to 64 bits)");
  s.length = static_cast<uint32_t>(*length);
  const DbcToken order = lex_.peek();
  if (!order.is(DbcTokenKind::kNumber, "0") && !order.is(DbcTokenKind::kNumber, "1"))
    return fail_at(order, "the byte order, 1 (Intel) or 0 (Motorola)");
  lex_.take();
  s.byte_order = order.text == "1" ? ByteOrder::kIntel : ByteOrder::kMotorola;
  const DbcToken sign = lex_.peek();
  if (!sign.is_punct('+') && !sign.is_punct('-')) return fail_at(sign, "'+' (unsigned) or '-' (signed)");
  lex_.take();
  s.is_signed = sign.is_punct('-');
  return true;
}

// (factor,offset) [min|max] "unit".
bool DbcReader::signal_scaling(DbcSignal& s) {
  if (!expect_punct('(')) return false;
  const auto factor = number<double>("the factor", "a number");
  if (!factor || !expect_punct(',')) return false;
  const auto offset = number<double>("the offset", "a number");
  if (!offset || !expect_punct(')') || !expect_punct('[')) return false;
  const auto minimum = number<double>("the minimum", "a number");
  if (!minimum || !expect_punct('|')) return false;
  const auto maximum = number<double>("the maximum", "a number");
  if (!maximum || !expect_punct(']')) return false;
  const auto unit = expect(DbcTokenKind::kString, "the unit (a string)");
  if (!unit) return false;
  s.factor = *factor;
  s.offset = *offset;
  s.minimum = *minimum;
  s.maximum = *maximum;
  s.unit = unescape_dbc_string(unit->text);
  return true;
}

// Receiving nodes to the end of the line, separated by commas (or spaces, as some tools write).
bool DbcReader::signal_receivers(DbcSignal& s) {
  while (on_same_line()) {
    if (lex_.peek().is_punct(',')) {
      lex_.take();
      continue;
    }
    const auto node = expect(DbcTokenKind::kIdentifier, "a receiving node");
    if (!node) return false;
    s.receivers.emplace_back(node->text);
  }
  return true;
}

}  // namespace brickyard::vehicle_interface::dbc_detail
