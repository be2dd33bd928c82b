#include "dbc_lexer.hpp"

namespace brickyard::vehicle_interface {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_identifier_start(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool is_identifier_char(char c) { return is_identifier_start(c) || is_digit(c); }
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
bool is_punct(char c) {
  switch (c) {
    case ':': case '|': case '@': case '(': case ')': case '[': case ']': case ',': case ';':
    case '+': case '-': return true;
    default: return false;
  }
}

}  // namespace

void DbcLexer::skip_space() {
  while (at_ < text_.size() && is_space(text_[at_])) {
    if (text_[at_] == '\n') {
      ++line_;
      line_begin_ = at_ + 1;
    }
    ++at_;
  }
}

// [+-] digits [. digits] [e [+-] digits], or [+-] . digits [...]: a sign is the number's only
// when a digit (or a point and a digit) follows it, so "@1-" stays '@', 1, '-'.
bool DbcLexer::number_starts_at(size_t at) const {
  auto digit_at = [&](size_t i) { return i < text_.size() && is_digit(text_[i]); };
  if (at < text_.size() && (text_[at] == '+' || text_[at] == '-')) ++at;
  if (digit_at(at)) return true;
  return at < text_.size() && text_[at] == '.' && digit_at(at + 1);
}

size_t DbcLexer::number_end(size_t at) const {
  auto skip_digits = [&](size_t i) {
    while (i < text_.size() && is_digit(text_[i])) ++i;
    return i;
  };
  if (text_[at] == '+' || text_[at] == '-') ++at;
  at = skip_digits(at);
  if (at < text_.size() && text_[at] == '.') at = skip_digits(at + 1);
  if (at < text_.size() && (text_[at] == 'e' || text_[at] == 'E')) {
    size_t exponent = at + 1;
    if (exponent < text_.size() && (text_[exponent] == '+' || text_[exponent] == '-')) ++exponent;
    if (exponent < text_.size() && is_digit(text_[exponent])) at = skip_digits(exponent);
  }
  return at;
}

// From the opening quote to the closing one, over line ends; a backslash keeps the next byte in.
// With no closing quote the token is kBad, "string not closed", at the line it opened on.
DbcToken DbcLexer::scan_string(DbcToken t) {
  size_t i = at_ + 1;
  int lines = 0;
  size_t last_line_begin = line_begin_;
  while (i < text_.size() && text_[i] != '"') {
    if (text_[i] == '\\' && i + 1 < text_.size()) ++i;
    if (text_[i] == '\n') {
      ++lines;
      last_line_begin = i + 1;
    }
    ++i;
  }
  if (i >= text_.size()) {
    t.kind = DbcTokenKind::kBad;
    t.text = "string not closed";
    at_ = text_.size();
    return t;
  }
  t.kind = DbcTokenKind::kString;
  t.text = text_.substr(at_ + 1, i - at_ - 1);
  line_ += lines;
  line_begin_ = last_line_begin;
  at_ = i + 1;
  return t;
}

void DbcLexer::advance() {
  skip_space();
  DbcToken t;
  t.line = line_;
  t.first_on_line = line_ != last_token_line_;
  t.at_line_start = at_ == line_begin_;
  if (at_ >= text_.size()) {
    next_ = t;
    return;
  }
  const char c = text_[at_];
  size_t end = at_ + 1;
  if (c == '"') {
    t = scan_string(t);
    last_token_line_ = line_;  // a string's last line is where the next token's line is compared
    next_ = t;
    return;
  }
  if (is_identifier_start(c)) {
    while (end < text_.size() && is_identifier_char(text_[end])) ++end;
    t.kind = DbcTokenKind::kIdentifier;
  } else if (number_starts_at(at_)) {
    end = number_end(at_);
    t.kind = DbcTokenKind::kNumber;
  } else {
    t.kind = is_punct(c) ? DbcTokenKind::kPunct : DbcTokenKind::kBad;
  }
  t.text = text_.substr(at_, end - at_);
  at_ = end;
  last_token_line_ = t.line;
  next_ = t;
}

std::string unescape_dbc_string(std::string_view raw) {
  std::string out;
  out.reserve(raw.size());
  for (size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] == '\\' && i + 1 < raw.size() && (raw[i + 1] == '"' || raw[i + 1] == '\\')) ++i;
    out.push_back(raw[i]);
  }
  return out;
}

}  // namespace brickyard::vehicle_interface
