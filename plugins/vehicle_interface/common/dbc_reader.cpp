// The DBC reader's loop: statements one after another, each checked as it is read, every problem
// an error at its line; reading goes on at the next line, up to DbcLimits::max_errors. The
// format as learned from public descriptions: docs/can-dbc.md.
#include "dbc_reader.hpp"

#include "io/bounded_read.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>

namespace brickyard::vehicle_interface {

namespace dbc_detail {

namespace {

// Statements read past up to their ';': attributes, value tables, signal groups, environment
// variables, relations. None changes how a frame is packed.
constexpr std::array<std::string_view, 23> kSkippedStatements = {
    "VAL_TABLE_", "BA_DEF_", "BA_", "BA_DEF_DEF_", "BA_DEF_REL_", "BA_REL_", "BA_DEF_DEF_REL_",
    "BA_DEF_SGTYPE_", "BA_SGTYPE_", "SIGTYPE_VALTYPE_", "SIG_GROUP_", "SIG_TYPE_REF_", "SGTYPE_",
    "SGTYPE_VAL_", "BO_TX_BU_", "EV_", "ENVVAR_DATA_", "CAT_DEF_", "CAT_", "FILTER", "NS_DESC_",
    "BU_SG_REL_", "BU_BO_REL_"};

std::string describe_byte(unsigned char c) {
  if (c >= 32 && c <= 126) return std::string("'") + static_cast<char>(c) + "'";
  char hex[8];
  std::snprintf(hex, sizeof hex, "\\x%02x", c);
  return std::string("byte ") + hex;
}

}  // namespace

std::string describe(const DbcToken& t) {
  switch (t.kind) {
    case DbcTokenKind::kEnd: return "the end of the file";
    case DbcTokenKind::kString: return "a string";
    case DbcTokenKind::kBad:
      return t.text.size() == 1 ? describe_byte(static_cast<unsigned char>(t.text[0])) : std::string(t.text);
    default: return "'" + std::string(t.text.substr(0, 40)) + (t.text.size() > 40 ? "...'" : "'");
  }
}

DbcReadResult DbcReader::run() {
  while (lex_.peek().kind != DbcTokenKind::kEnd && !full()) {
    const size_t errors_before = errors_.size();
    context_.clear();
    statement();
    if (errors_.size() > errors_before) skip_to_next_line();
  }
  if (!full()) check_layouts();
  std::stable_sort(errors_.begin(), errors_.end(), [](const DbcError& a, const DbcError& b) { return a.line < b.line; });
  if (errors_.size() > limits_.max_errors) errors_.resize(limits_.max_errors);
  DbcReadResult result;
  result.errors = std::move(errors_);
  if (result.errors.empty()) result.database = std::move(db_);
  return result;
}

bool DbcReader::fail(int line, std::string what) {
  errors_.push_back({std::string(file_), line, context_ + what});
  return false;
}

bool DbcReader::fail_at(const DbcToken& t, const std::string& expected) {
  return fail(t.line, "expected " + expected + ", found " + describe(t));
}

void DbcReader::skip_to_next_line() {
  while (on_same_line()) lex_.take();
}

bool DbcReader::expect_punct(char c) {
  if (!lex_.peek().is_punct(c)) return fail_at(lex_.peek(), std::string("'") + c + "'");
  lex_.take();
  return true;
}

std::optional<DbcToken> DbcReader::expect(DbcTokenKind kind, const std::string& what) {
  if (lex_.peek().kind == kind) return lex_.take();
  fail_at(lex_.peek(), what);
  return std::nullopt;
}

void DbcReader::statement() {
  const DbcToken t = lex_.peek();
  if (t.kind != DbcTokenKind::kIdentifier) {
    fail(t.line, "expected a keyword, found " + describe(t));
    lex_.take();
    return;
  }
  if (!t.is_keyword("SG_")) open_message_.reset(), skipping_signals_ = false;
  if (t.is_keyword("VERSION")) version();
  else if (t.is_keyword("NS_")) new_symbols();
  else if (t.is_keyword("BS_")) lex_.take(), skip_to_next_line();  // bit timing: obsolete, unused
  else if (t.is_keyword("BU_")) nodes();
  else if (t.is_keyword("BO_")) message();
  else if (t.is_keyword("SG_")) signal();
  else if (t.is_keyword("CM_")) comment();
  else if (t.is_keyword("VAL_")) value_names();
  else if (t.is_keyword("SIG_VALTYPE_")) value_type();
  else if (t.is_keyword("SG_MUL_VAL_")) extended_multiplexing();
  else if (std::find(kSkippedStatements.begin(), kSkippedStatements.end(), t.text) != kSkippedStatements.end())
    lex_.take(), skip_statement(t.line, t.text);
  else
    fail(t.line, "unknown keyword " + describe(t)), lex_.take();
}

bool DbcReader::version() {
  lex_.take();
  const auto text = expect(DbcTokenKind::kString, "the version string");
  if (text) db_.version = unescape_dbc_string(text->text);
  return text.has_value();
}

// "NS_ :" and the names of new symbols, one per indented line: read past up to the first line
// that starts at its first column (the names are keywords themselves: indentation ends the list).
bool DbcReader::new_symbols() {
  lex_.take();
  while (lex_.peek().kind != DbcTokenKind::kEnd && !lex_.peek().at_line_start) lex_.take();
  return true;
}

bool DbcReader::nodes() {
  lex_.take();
  if (!expect_punct(':')) return false;
  while (on_same_line()) {
    const auto node = expect(DbcTokenKind::kIdentifier, "a node name");
    if (!node) return false;
    db_.nodes.emplace_back(node->text);
  }
  return true;
}

bool DbcReader::skip_statement(int line, std::string_view keyword) {
  while (!lex_.peek().is_punct(';')) {
    const DbcToken t = lex_.take();
    if (t.kind == DbcTokenKind::kBad) return fail(t.line, describe(t));
    if (t.kind == DbcTokenKind::kEnd) return fail(line, std::string(keyword) + " not ended by ';'");
  }
  lex_.take();
  return true;
}

}  // namespace dbc_detail

std::string DbcError::text() const { return file + ":" + std::to_string(line) + ": " + what; }

DbcReadResult parse_dbc(std::string_view text, std::string_view file_name, DbcLimits limits) {
  if (limits.max_errors == 0) limits.max_errors = 1;
  if (text.size() > limits.max_file_bytes) {
    DbcReadResult result;
    result.errors.push_back({std::string(file_name), 0,
                             "file of " + std::to_string(text.size()) + " bytes or more, over the limit of " +
                                 std::to_string(limits.max_file_bytes)});
    return result;
  }
  return dbc_detail::DbcReader(text, file_name, limits).run();
}

DbcReadResult load_dbc_file(const std::string& path, DbcLimits limits) {
  const std::string name = path.substr(path.find_last_of('/') + 1);
  std::string error;
  std::ifstream in;
  if (io::is_regular_readable(path, error)) in.open(path, std::ios::binary);
  if (!in.is_open()) {
    DbcReadResult result;
    result.errors.push_back({name, 0, error.empty() ? "cannot open " + path : error});
    return result;
  }
  std::string text;
  char chunk[65536];
  while (text.size() <= limits.max_file_bytes && (in.read(chunk, sizeof chunk) || in.gcount() > 0))
    text.append(chunk, static_cast<size_t>(in.gcount()));  // past the limit parse_dbc refuses it unread
  return parse_dbc(text, name, limits);
}

}  // namespace brickyard::vehicle_interface
