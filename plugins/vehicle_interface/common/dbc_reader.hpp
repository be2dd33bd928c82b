#pragma once
// Inside parse_dbc (dbc.hpp): the reader's state and its statements, split over
// dbc_reader.cpp (the loop, tokens, skipped statements), dbc_messages.cpp (BO_ and SG_) and
// dbc_annotations.cpp (CM_, VAL_, SIG_VALTYPE_, SG_MUL_VAL_ and the checks at the end).
#include "dbc.hpp"
#include "dbc_lexer.hpp"

#include <charconv>
#include <cstdint>
#include <optional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace brickyard::vehicle_interface::dbc_detail {

inline constexpr uint64_t kExtendedIdFlag = 0x80000000u;  // bit 31 of a message id in the file

std::string describe(const DbcToken& t);

class DbcReader {
 public:
  DbcReader(std::string_view text, std::string_view file, DbcLimits limits) : lex_(text), file_(file), limits_(limits) {}
  DbcReadResult run();

 private:
  bool full() const { return errors_.size() >= limits_.max_errors; }
  bool fail(int line, std::string what);
  bool fail_at(const DbcToken& t, const std::string& expected);
  void skip_to_next_line();
  bool on_same_line() const { return lex_.peek().kind != DbcTokenKind::kEnd && !lex_.peek().first_on_line; }
  bool expect_punct(char c);
  std::optional<DbcToken> expect(DbcTokenKind kind, const std::string& what);

  // The next token as a number of type T (uint64_t, int64_t or double), or an error naming `what`.
  template <typename T>
  std::optional<T> number(const std::string& what, const char* form) {
    const DbcToken t = lex_.peek();
    std::string_view text = t.text;
    if (!text.empty() && text[0] == '+') text.remove_prefix(1);  // from_chars takes no '+'
    T value{};
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (t.kind != DbcTokenKind::kNumber || ec != std::errc() || end != text.data() + text.size()) {
      fail_at(t, what + " (" + form + ")");
      return std::nullopt;
    }
    lex_.take();
    return value;
  }

  void statement();
  bool version();
  bool new_symbols();
  bool nodes();
  bool skip_statement(int line, std::string_view keyword);
  bool message();
  bool message_id(DbcMessage& m, uint64_t file_id, int line);
  bool signal();
  bool signal_multiplexing(DbcSignal& s);
  bool signal_layout(DbcSignal& s);
  bool signal_scaling(DbcSignal& s);
  bool signal_receivers(DbcSignal& s);
  bool comment();
  bool value_names();
  bool value_type();
  bool extended_multiplexing();
  DbcMessage* message_for(uint64_t file_id, int line, std::string_view what);
  DbcSignal* signal_for(DbcMessage& m, std::string_view name, int line, std::string_view what);
  void check_layouts();

  DbcLexer lex_;
  std::string_view file_;
  DbcLimits limits_;
  DbcDatabase db_;
  std::vector<DbcError> errors_;
  std::optional<size_t> open_message_;  // the BO_ whose SG_ lines are being read
  bool skipping_signals_ = false;       // a BO_ line was refused: its SG_ lines are passed over
  std::string context_;                 // "signal X: ", put before the errors of a statement
  std::map<std::pair<uint32_t, bool>, size_t> message_index_;  // (id, extended) -> messages[i]
  std::vector<std::map<std::string, size_t, std::less<>>> signal_index_;  // per message: name -> signals[i]
  std::set<std::string, std::less<>> message_names_;
};

}  // namespace brickyard::vehicle_interface::dbc_detail
