#include "cdr/cdr_json.hpp"

#include <cctype>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <stdexcept>

namespace brickyard::cdr {

namespace {

// Reading CDR: alignment from the first byte after the encapsulation header.
struct Reader {
  const unsigned char* p;
  std::size_t n, at = 4;
  bool little = true;
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(what + " at byte " + std::to_string(at) + " of " + std::to_string(n));
  }
  void align(std::size_t k) {
    const std::size_t off = (at - 4) % k;
    if (off) at += k - off;
  }
  const unsigned char* take(std::size_t k) {
    if (at > n || n - at < k) fail("the sample ends early");
    const unsigned char* q = p + at;
    at += k;
    return q;
  }
  template <typename T>
  T num() {
    align(sizeof(T));
    const unsigned char* q = take(sizeof(T));
    unsigned char b[sizeof(T)];
    for (std::size_t i = 0; i < sizeof(T); ++i) b[i] = little ? q[i] : q[sizeof(T) - 1 - i];
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }
};

using Type = CdrJson::Type;
using Member = CdrJson::Member;
using StructMap = IdlStructs;

}  // namespace

CdrJson::CdrJson(const std::string& idl) : structs_(parse_idl(idl).structs) {}

nlohmann::json CdrJson::decode(const std::string& type, const unsigned char* data, std::size_t size) const {
  Reader r{data, size};
  if (size < 4) r.fail("no encapsulation header");
  if (data[0] != 0 || data[1] > 1) r.fail("not plain CDR (encapsulation " + std::to_string(data[0]) + " " + std::to_string(data[1]) + ")");
  r.little = data[1] == 1;
  std::function<nlohmann::json(const Type&)> value;
  int depth = 0;
  std::function<nlohmann::json(const std::string&)> object = [&](const std::string& name) {
    if (++depth > 64) r.fail("structs nested more than 64 deep");
    const auto it = structs_.find(name);
    if (it == structs_.end()) throw std::runtime_error("no struct '" + name + "' in the IDL");
    nlohmann::json o = nlohmann::json::object();
    for (const Member& m : *it->second) o[m.name] = value(m.type);
    --depth;
    return o;
  };
  value = [&](const Type& ty) -> nlohmann::json {
    switch (ty.kind) {
      case Type::Primitive: {
        const std::string& n = ty.name;
        if (n == "double") return r.num<double>();
        if (n == "float") return r.num<float>();
        if (n == "boolean") return r.num<std::uint8_t>() != 0;
        if (n == "int8") return r.num<std::int8_t>();
        if (n == "uint8" || n == "octet" || n == "char") return r.num<std::uint8_t>();
        if (n == "int16" || n == "short") return r.num<std::int16_t>();
        if (n == "uint16") return r.num<std::uint16_t>();
        if (n == "int32" || n == "long") return r.num<std::int32_t>();
        if (n == "uint32") return r.num<std::uint32_t>();
        if (n == "int64") return r.num<std::int64_t>();
        return r.num<std::uint64_t>();
      }
      case Type::String: {
        const std::uint32_t len = r.num<std::uint32_t>();
        const unsigned char* q = r.take(len);
        return std::string(reinterpret_cast<const char*>(q), len > 0 && q[len - 1] == '\0' ? len - 1 : len);
      }
      case Type::Struct:
        return object(ty.name);
      case Type::Sequence:
      case Type::Array: {
        const std::size_t count = ty.kind == Type::Array ? ty.size : r.num<std::uint32_t>();
        // Each element takes at least a byte: a count past what is left is damage, not an allocation.
        if (count > r.n - std::min(r.at, r.n)) r.fail("a sequence of " + std::to_string(count) + " elements");
        nlohmann::json a = nlohmann::json::array();
        for (std::size_t k = 0; k < count; ++k) a.push_back(value(*ty.of));
        return a;
      }
    }
    return nullptr;
  };
  return object(idl_bare_name(type));
}

namespace {

// Writing CDR: little-endian, each primitive aligned to its size from the end of the header.
struct Writer {
  std::vector<unsigned char> out{0, 1, 0, 0};
  void align(std::size_t k) {
    while ((out.size() - 4) % k) out.push_back(0);
  }
  template <typename T>
  void num(T v) {
    align(sizeof(T));
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.insert(out.end(), b, b + sizeof(T));  // this host is little-endian (x86-64, arm64)
  }
};

// Writes one sample from JSON, member by member in the IDL's order; `where` is the JSON pointer of
// the value at hand, for the errors.
class Encoder {
 public:
  explicit Encoder(const StructMap& structs) : structs_(structs) {}

  std::vector<unsigned char> encode(const std::string& type, const nlohmann::json& sample) {
    object(idl_bare_name(type), &sample, "");
    return w_.out;
  }

 private:
  [[noreturn]] static void bad(const std::string& where, const std::string& what, const nlohmann::json* v) {
    throw std::invalid_argument((where.empty() ? "/" : where) + ": " + what + (v ? ", found " + v->dump().substr(0, 60) : ""));
  }

  void object(const std::string& name, const nlohmann::json* v, const std::string& where) {
    if (++depth_ > 64) bad(where, "structs nested more than 64 deep", nullptr);
    const auto it = structs_.find(name);
    if (it == structs_.end()) throw std::invalid_argument("no struct '" + name + "' in the IDL");
    if (v && !v->is_object()) bad(where, "expected an object (" + name + ")", v);
    if (v) reject_unknown_members(name, *it->second, *v, where);
    for (const Member& m : *it->second) {
      const nlohmann::json* x = v && v->contains(m.name) ? &(*v)[m.name] : nullptr;
      value(m.type, x, where + "/" + m.name);
    }
    --depth_;
  }

  static void reject_unknown_members(const std::string& name, const std::vector<Member>& members, const nlohmann::json& v,
                                     const std::string& where) {
    for (const auto& [key, x] : v.items()) {
      bool known = false;
      for (const Member& m : members) known = known || m.name == key;
      if (!known) {
        std::string have;
        for (const Member& m : members) have += (have.empty() ? "" : ", ") + m.name;
        bad(where + "/" + key, "no member '" + key + "' in " + name + " (members: " + have + ")", nullptr);
      }
    }
  }

  void value(const Type& ty, const nlohmann::json* v, const std::string& where) {
    switch (ty.kind) {
      case Type::Primitive:
        return primitive(ty.name, v, where);
      case Type::String:
        return string_value(v, where);
      case Type::Struct:
        return object(ty.name, v, where);
      case Type::Sequence:
      case Type::Array:
        return elements(ty, v, where);
    }
  }

  void primitive(const std::string& n, const nlohmann::json* v, const std::string& where) {
    if (n == "boolean") {
      if (v && !v->is_boolean()) bad(where, "expected true or false", v);
      return w_.num<std::uint8_t>(v && v->get<bool>() ? 1 : 0);
    }
    if (v && !v->is_number()) bad(where, "expected a number", v);
    const double d = v ? v->get<double>() : 0.0;
    if (n == "double") return w_.num<double>(d);
    if (n == "float") return w_.num<float>(static_cast<float>(d));
    // Integers: whole, and within the type's range (int64 and uint64 from JSON's integers).
    auto whole = [&](double lo, double hi) {
      if (v && !(v->is_number_integer() || (d == std::floor(d) && d >= lo && d <= hi))) bad(where, "expected a whole number", v);
      if (d < lo || d > hi) bad(where, "out of " + n + "'s range", v);
    };
    if (n == "int64") {
      if (v && !v->is_number_integer()) bad(where, "expected an integer", v);
      return w_.num<std::int64_t>(v ? v->get<std::int64_t>() : 0);
    }
    if (n == "uint64") {
      if (v && !v->is_number_unsigned() && !(v->is_number_integer() && v->get<std::int64_t>() >= 0))
        bad(where, "expected an integer >= 0", v);
      return w_.num<std::uint64_t>(v ? v->get<std::uint64_t>() : 0);
    }
    if (n == "int8") return whole(-128, 127), w_.num<std::int8_t>(static_cast<std::int8_t>(d));
    if (n == "uint8" || n == "octet" || n == "char") return whole(0, 255), w_.num<std::uint8_t>(static_cast<std::uint8_t>(d));
    if (n == "int16" || n == "short") return whole(-32768, 32767), w_.num<std::int16_t>(static_cast<std::int16_t>(d));
    if (n == "uint16") return whole(0, 65535), w_.num<std::uint16_t>(static_cast<std::uint16_t>(d));
    if (n == "int32" || n == "long") return whole(-2147483648.0, 2147483647.0), w_.num<std::int32_t>(static_cast<std::int32_t>(d));
    return whole(0, 4294967295.0), w_.num<std::uint32_t>(static_cast<std::uint32_t>(d));
  }

  void string_value(const nlohmann::json* v, const std::string& where) {
    if (v && !v->is_string()) bad(where, "expected a string", v);
    const std::string text = v ? v->get<std::string>() : std::string();
    w_.num<std::uint32_t>(static_cast<std::uint32_t>(text.size() + 1));
    w_.out.insert(w_.out.end(), text.begin(), text.end());
    w_.out.push_back(0);
  }

  // A sequence (its count first) or a fixed array (its length from the type).
  void elements(const Type& ty, const nlohmann::json* v, const std::string& where) {
    if (v && !v->is_array()) bad(where, "expected a list", v);
    const std::size_t count = v ? v->size() : 0;
    if (ty.kind == Type::Array && v && count != ty.size) bad(where, "expected " + std::to_string(ty.size) + " elements", v);
    if (ty.kind == Type::Sequence) w_.num<std::uint32_t>(static_cast<std::uint32_t>(count));
    const std::size_t n = ty.kind == Type::Array ? ty.size : count;
    for (std::size_t k = 0; k < n; ++k) value(*ty.of, v ? &(*v)[k] : nullptr, where + "/" + std::to_string(k));
  }

  const StructMap& structs_;
  Writer w_;
  int depth_ = 0;
};

}  // namespace

std::vector<unsigned char> CdrJson::encode(const std::string& type, const nlohmann::json& sample) const {
  return Encoder(structs_).encode(type, sample);
}

std::string CdrJson::field_kind(const std::string& type, const FieldPath& path) const {
  auto it = structs_.find(idl_bare_name(type));
  if (it == structs_.end()) throw std::invalid_argument("no struct '" + type + "' in the IDL");
  std::string struct_name = idl_bare_name(type);
  const std::vector<Member>* members = it->second.get();
  const Type* ty = nullptr;
  for (std::size_t s = 0; s < path.steps.size(); ++s) {
    const auto& st = path.steps[s];
    if (!members) throw std::invalid_argument(path.text + ": '" + path.steps[s - 1].member + "' has no members");
    const Member* m = nullptr;
    for (const auto& x : *members)
      if (x.name == st.member) m = &x;
    if (!m) {
      std::string have;
      for (const auto& x : *members) have += (have.empty() ? "" : ", ") + x.name;
      throw std::invalid_argument(path.text + ": no member '" + st.member + "' in " + struct_name + " (members: " + have + ")");
    }
    ty = &m->type;
    for (std::size_t k = 0; k < st.index.size(); ++k) {
      if (ty->kind != Type::Sequence && ty->kind != Type::Array)
        throw std::invalid_argument(path.text + ": '" + st.member + "' is not a sequence or an array; it takes no index");
      if (ty->kind == Type::Array && st.index[k] != FieldPath::kEvery && static_cast<std::size_t>(st.index[k]) >= ty->size)
        throw std::invalid_argument(path.text + ": '" + st.member + "' has " + std::to_string(ty->size) + " elements");
      ty = ty->of.get();
    }
    members = nullptr;
    if (ty->kind == Type::Struct) {
      struct_name = ty->name;
      members = structs_.at(ty->name).get();
    }
  }
  switch (ty->kind) {
    case Type::Primitive: return ty->name == "boolean" ? "boolean" : "number";
    case Type::String: return "string";
    case Type::Struct: return "struct";
    default: return "sequence";
  }
}

}  // namespace brickyard::cdr
