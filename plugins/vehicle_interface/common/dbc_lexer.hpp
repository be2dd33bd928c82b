#pragma once
// The words of a DBC file (dbc_reader.cpp's input): identifiers, numbers, quoted strings (which
// may run over several lines, as comments do) and the format's punctuation, each with its line.
// Bytes that start none of them come back as kBad tokens; nothing is thrown.
#include <cstddef>
#include <string>
#include <string_view>

namespace brickyard::vehicle_interface {

enum class DbcTokenKind { kEnd, kIdentifier, kNumber, kString, kPunct, kBad };

struct DbcToken {
  DbcTokenKind kind = DbcTokenKind::kEnd;
  std::string_view text;  // a string's text without its quotes, escapes not yet undone
  int line = 1;           // where the token starts
  bool first_on_line = false;  // no token before it on its line
  bool at_line_start = false;  // and not indented

  bool is(DbcTokenKind k, std::string_view t) const { return kind == k && text == t; }
  bool is_punct(char c) const { return kind == DbcTokenKind::kPunct && text.size() == 1 && text[0] == c; }
  bool is_keyword(std::string_view word) const { return is(DbcTokenKind::kIdentifier, word); }
};

class DbcLexer {
 public:
  explicit DbcLexer(std::string_view text) : text_(text) { advance(); }

  const DbcToken& peek() const { return next_; }
  DbcToken take() {
    DbcToken t = next_;
    advance();
    return t;
  }

 private:
  void advance();
  void skip_space();
  DbcToken scan_string(DbcToken t);
  bool number_starts_at(size_t at) const;
  size_t number_end(size_t at) const;

  std::string_view text_;
  size_t at_ = 0;
  int line_ = 1;
  size_t line_begin_ = 0;     // offset where line_ begins
  int last_token_line_ = 0;   // line of the token before next_
  DbcToken next_;
};

// A DBC string's text with its escapes (\" and \\) undone.
std::string unescape_dbc_string(std::string_view raw);

}  // namespace brickyard::vehicle_interface
