#include "cdr/idl_model.hpp"

#include <cctype>
#include <set>
#include <sstream>
#include <stdexcept>

namespace brickyard::cdr {

namespace {

struct Token {
  std::string text;
  int line;
};

std::vector<Token> tokenize(const std::string& idl) {
  std::vector<Token> out;
  int line = 1;
  for (std::size_t i = 0; i < idl.size();) {
    const char c = idl[i];
    if (c == '\n') ++line, ++i;
    else if (std::isspace(static_cast<unsigned char>(c))) ++i;
    else if (c == '#' || (c == '/' && i + 1 < idl.size() && idl[i + 1] == '/')) {  // a directive or a comment: to the line's end
      while (i < idl.size() && idl[i] != '\n') ++i;
    } else if (c == '/' && i + 1 < idl.size() && idl[i + 1] == '*') {
      const std::size_t end = idl.find("*/", i + 2);
      for (std::size_t k = i; k < std::min(end, idl.size()); ++k) line += idl[k] == '\n';
      i = end == std::string::npos ? idl.size() : end + 2;
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == ':') {
      std::size_t j = i;
      while (j < idl.size() && (std::isalnum(static_cast<unsigned char>(idl[j])) || idl[j] == '_' || idl[j] == ':')) ++j;
      out.push_back({idl.substr(i, j - i), line});
      i = j;
    } else {
      out.push_back({std::string(1, c), line});
      ++i;
    }
  }
  return out;
}

std::size_t primitive_size(const std::string& t) {
  static const std::map<std::string, std::size_t> sizes = {
      {"boolean", 1}, {"octet", 1}, {"char", 1}, {"int8", 1}, {"uint8", 1}, {"int16", 2}, {"uint16", 2}, {"short", 2},
      {"int32", 4}, {"uint32", 4}, {"long", 4}, {"float", 4}, {"int64", 8}, {"uint64", 8}, {"double", 8}};
  const auto it = sizes.find(t);
  return it == sizes.end() ? 0 : it->second;
}

std::string bare_of(const std::string& name) {
  const auto at = name.rfind("::");
  return at == std::string::npos ? name : name.substr(at + 2);
}

// Reads the IDL's tokens front to back into `structs`; each error names the line of the token it
// stopped at (the last line at the end of the text).
class IdlParser {
 public:
  IdlParser(std::vector<Token> tokens, IdlModel& model) : t_(std::move(tokens)), model_(model) {}

  void parse() {
    while (i_ < t_.size()) {
      if (t_[i_].text == "module") {
        open_module();
      } else if (t_[i_].text == "}" && !scope_.empty()) {
        close_module();
      } else if (t_[i_].text == "struct") {
        struct_definition();
      } else {
        fail("expected module, struct or the end of a module, found '" + t_[i_].text + "'");
      }
    }
    if (!scope_.empty()) fail("module '" + scope_.back() + "' is not closed");
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    const int line = i_ < t_.size() ? t_[i_].line : (t_.empty() ? 1 : t_.back().line);
    throw std::invalid_argument("IDL line " + std::to_string(line) + ": " + what);
  }
  void expect(const std::string& s) {
    if (i_ >= t_.size() || t_[i_].text != s) fail("expected '" + s + "'" + (i_ < t_.size() ? ", found '" + t_[i_].text + "'" : ""));
    ++i_;
  }
  std::size_t number() {
    if (i_ >= t_.size() || t_[i_].text.empty() || t_[i_].text.size() > 9 ||
        t_[i_].text.find_first_not_of("0123456789") != std::string::npos)
      fail("expected a number (at most 9 digits)");
    return static_cast<std::size_t>(std::stoul(t_[i_++].text));
  }

  void open_module() {
    ++i_;
    if (i_ >= t_.size()) fail("expected a module name");
    scope_.push_back(t_[i_++].text);
    expect("{");
  }
  void close_module() {
    ++i_;
    expect(";");
    scope_.pop_back();
  }

  IdlType type() {
    if (i_ >= t_.size()) fail("expected a type");
    const std::string name = t_[i_++].text;
    IdlType ty;
    if (name == "sequence") {
      expect("<");
      ty.kind = IdlType::Sequence;
      ty.of = std::make_shared<IdlType>(type());
      if (i_ < t_.size() && t_[i_].text == ",") ++i_, ty.bound = number();  // kept, not checked on samples
      expect(">");
    } else if (name == "string") {
      ty.kind = IdlType::String;
      if (i_ < t_.size() && t_[i_].text == "<") ++i_, ty.bound = number(), expect(">");
    } else if (const std::size_t k = primitive_size(name)) {
      ty.kind = IdlType::Primitive, ty.name = name, ty.size = k;
    } else {
      if (!model_.structs.count(name) && !model_.structs.count(bare_of(name))) fail("unknown type '" + name + "' (defined after its use?)");
      ty.kind = IdlType::Struct, ty.name = bare_of(name);
    }
    return ty;
  }

  // A member: its type, its name, then a fixed array's length when it has one.
  IdlMember member() {
    IdlMember m;
    m.type = type();
    if (i_ >= t_.size()) fail("expected a member name");
    m.name = t_[i_++].text;
    if (i_ < t_.size() && t_[i_].text == "[") {
      ++i_;
      auto el = std::make_shared<IdlType>(m.type);
      m.type = IdlType{};
      m.type.kind = IdlType::Array;
      m.type.size = number();
      m.type.of = el;
      expect("]");
    }
    expect(";");
    return m;
  }

  void struct_definition() {
    ++i_;
    if (i_ >= t_.size()) fail("expected a struct name");
    const std::string name = t_[i_++].text;
    expect("{");
    std::vector<IdlMember> members;
    while (i_ < t_.size() && t_[i_].text != "}") members.push_back(member());
    expect("}");
    expect(";");
    std::string qualified;
    for (const auto& s : scope_) qualified += s + "::";
    // An IDL is untrusted input (a recording's schema): a struct defined twice could make a
    // cycle, one with no members an endless count of nothing.
    if (model_.structs.count(qualified + name)) fail("struct '" + qualified + name + "' is defined twice");
    if (members.empty()) fail("struct '" + name + "' has no members");
    auto def = std::make_shared<std::vector<IdlMember>>(std::move(members));
    model_.structs[qualified + name] = def;
    model_.structs[name] = def;
    model_.defined.push_back(qualified + name);
  }

  const std::vector<Token> t_;
  std::size_t i_ = 0;
  std::vector<std::string> scope_;
  IdlModel& model_;
};

}  // namespace

std::string idl_bare_name(const std::string& name) { return bare_of(name); }

IdlModel parse_idl(const std::string& idl) {
  IdlModel model;
  IdlParser(tokenize(idl), model).parse();
  return model;
}

std::string self_contained_idl(const std::string& idl) {
  // Reversed, every definition comes after what it uses. Foxglove's IDL parser takes no #include.
  std::vector<std::string> blocks;
  std::string block, line;
  std::istringstream in(idl);
  while (std::getline(in, line)) {
    if (line.rfind("#include", 0) == 0) continue;
    block += line + "\n";
    if (line.find("}; };") != std::string::npos) blocks.push_back(std::move(block)), block.clear();
  }
  if (block.find_first_not_of(" \n") != std::string::npos) blocks.push_back(block);
  std::string out;
  std::set<std::string> seen;
  for (auto it = blocks.rbegin(); it != blocks.rend(); ++it)
    if (seen.insert(*it).second) out += *it;
  return out;
}

}  // namespace brickyard::cdr
