// What the DBC says about messages and signals after their BO_ and SG_ lines, each statement ended
// by ';', and the checks made once the whole file is read:
//   CM_ SG_ 1402 steering_motor_ang_cmd "motor angle command in deg.";
//   VAL_ 1343 driver_traction_aim_swicth_fbk -1 "Default" 0 "Zero" ;
//   SIG_VALTYPE_ 1402 some_signal : 1;
#include "dbc_checks.hpp"
#include "dbc_reader.hpp"

#include <map>

namespace brickyard::vehicle_interface::dbc_detail {

// CM_ "network comment"; CM_ BU_ node "..."; CM_ EV_ variable "..."; CM_ BO_ id "...";
// CM_ SG_ id signal "...". Nodes' and variables' comments are read past.
bool DbcReader::comment() {
  const int line = lex_.take().line;
  const DbcToken kind = lex_.peek();
  std::string* target = nullptr;
  if (kind.is_keyword("BU_") || kind.is_keyword("EV_")) {
    lex_.take();
    if (!expect(DbcTokenKind::kIdentifier, "a name")) return false;
  } else if (kind.is_keyword("BO_") || kind.is_keyword("SG_")) {
    lex_.take();
    const auto file_id = number<uint64_t>("the message id", "an unsigned integer");
    if (!file_id) return false;
    DbcMessage* m = message_for(*file_id, line, "comment");
    if (!m) return false;
    target = &m->comment;
    if (kind.is_keyword("SG_")) {
      const auto name = expect(DbcTokenKind::kIdentifier, "the signal name");
      DbcSignal* s = name ? signal_for(*m, name->text, line, "comment") : nullptr;
      if (!s) return false;
      target = &s->comment;
    }
  } else if (kind.kind != DbcTokenKind::kString) {
    return fail_at(kind, "BU_, BO_, SG_, EV_ or the comment");
  }
  const auto text = expect(DbcTokenKind::kString, "the comment (a string)");
  if (!text || !expect_punct(';')) return false;
  if (target) *target = unescape_dbc_string(text->text);
  return true;
}

// VAL_ id signal value "name" ... ; (an environment variable's, VAL_ variable ..., is read past).
bool DbcReader::value_names() {
  const int line = lex_.take().line;
  if (lex_.peek().kind == DbcTokenKind::kIdentifier) return skip_statement(line, "VAL_");
  const auto file_id = number<uint64_t>("the message id", "an unsigned integer");
  if (!file_id) return false;
  const auto name = expect(DbcTokenKind::kIdentifier, "the signal name");
  if (!name) return false;
  DbcMessage* m = message_for(*file_id, line, "value names");
  DbcSignal* s = m ? signal_for(*m, name->text, line, "value names") : nullptr;
  if (!s) return false;
  context_ = "signal " + s->name + ": ";
  std::map<int64_t, std::string> names;
  while (!lex_.peek().is_punct(';')) {
    const int value_line = lex_.peek().line;
    const auto value = number<int64_t>("a raw value or ';'", "an integer");
    if (!value) return false;
    const auto text = expect(DbcTokenKind::kString, "the value's name (a string)");
    if (!text) return false;
    if (!names.emplace(*value, unescape_dbc_string(text->text)).second)
      return fail(value_line, "value " + std::to_string(*value) + " named twice");
  }
  lex_.take();
  s->value_names = std::move(names);
  return true;
}

// SIG_VALTYPE_ id signal : 0|1|2 ; (integer, IEEE float, IEEE double).
bool DbcReader::value_type() {
  const int line = lex_.take().line;
  const auto file_id = number<uint64_t>("the message id", "an unsigned integer");
  if (!file_id) return false;
  const auto name = expect(DbcTokenKind::kIdentifier, "the signal name");
  if (!name) return false;
  DbcMessage* m = message_for(*file_id, line, "value type");
  DbcSignal* s = m ? signal_for(*m, name->text, line, "value type") : nullptr;
  if (!s) return false;
  context_ = "signal " + s->name + ": ";
  if (lex_.peek().is_punct(':')) lex_.take();
  const auto type = number<uint64_t>("the value type, 0, 1 or 2", "an unsigned integer");
  if (!type || !expect_punct(';')) return false;
  if (*type > 2) return fail(line, "value type " + std::to_string(*type) + " is none of 0 (integer), 1 (float), 2 (double)");
  s->value_type = static_cast<SignalValueType>(*type);
  if (const std::string problem = value_type_problem(*s); !problem.empty()) return fail(line, problem);
  return true;
}

// SG_MUL_VAL_ id signal multiplexer ranges ; marks the message as extended multiplexing.
bool DbcReader::extended_multiplexing() {
  const int line = lex_.take().line;
  const auto file_id = number<uint64_t>("the message id", "an unsigned integer");
  if (!file_id) return false;
  DbcMessage* m = message_for(*file_id, line, "extended multiplexing");
  if (!m) return false;
  m->extended_multiplexing = true;
  return skip_statement(line, "SG_MUL_VAL_");
}

DbcMessage* DbcReader::message_for(uint64_t file_id, int line, std::string_view what) {
  const uint32_t id = static_cast<uint32_t>(file_id & ~kExtendedIdFlag);
  const bool extended = (file_id & kExtendedIdFlag) != 0;
  const auto found = message_index_.find(std::pair(id, extended));
  if (found != message_index_.end() && file_id <= 0xFFFFFFFFu) return &db_.messages[found->second];
  fail(line, std::string(what) + " for message " + std::to_string(file_id) + ", which no BO_ defines");
  return nullptr;
}

DbcSignal* DbcReader::signal_for(DbcMessage& m, std::string_view name, int line, std::string_view what) {
  const auto& names = signal_index_[static_cast<size_t>(&m - db_.messages.data())];
  if (const auto found = names.find(name); found != names.end()) return &m.signals[found->second];
  fail(line, std::string(what) + " for signal " + std::string(name) + ", which message " + m.name + " does not have");
  return nullptr;
}

void DbcReader::check_layouts() {
  context_.clear();
  for (const DbcMessage& m : db_.messages)
    for (const LayoutProblem& p : message_layout_problems(m)) fail(p.line, "message " + m.name + ": " + p.what);
}

}  // namespace brickyard::vehicle_interface::dbc_detail
