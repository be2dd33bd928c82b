#pragma once
// A sample's CDR bytes as JSON, read by its type's IDL text (the text a recording and the live
// server carry): `brickyard topic echo` and `brickyard bag echo` print what they read without
// knowing the types at compile time. The IDL is the subset the message definitions use: modules,
// structs, the primitive types, string, sequence<T> and fixed arrays; CDR as Fast DDS writes it
// (XCDR1, either byte order, each primitive aligned to its size from the end of the 4-byte
// encapsulation header).
#include "cdr/field_path.hpp"
#include "cdr/idl_model.hpp"

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace brickyard::cdr {

class CdrJson {
 public:
  // Parses the IDL; throws std::invalid_argument naming the line of what it cannot read.
  explicit CdrJson(const std::string& idl);
  // Decodes one sample of `type` ("brickyard::msgs::Imu", or the bare name); throws
  // std::runtime_error naming the byte offset when the bytes do not fit the type.
  nlohmann::json decode(const std::string& type, const unsigned char* data, std::size_t size) const;

  // The other way: a sample of `type` from JSON, as CDR (XCDR1, little-endian, its encapsulation
  // header first) that Fast DDS's type support reads. A member the JSON leaves out is zero (an
  // empty string or sequence); one the type has not, a value of the wrong kind or out of its
  // type's range is std::invalid_argument naming its JSON pointer ("/poses/3/x: expected a
  // number, found \"a\"").
  std::vector<unsigned char> encode(const std::string& type, const nlohmann::json& sample) const;

  // What a field path reaches in `type`: "number", "boolean", "string", "struct" or "sequence"
  // (what is left of an array or sequence the path does not index). Throws std::invalid_argument
  // naming the step the type does not have, and what it has there ("no member 'posez' in Path
  // (members: header, poses, speeds)"; "'speeds' is a sequence: index it, [N] or [*]" is not an
  // error: it is a "sequence").
  std::string field_kind(const std::string& type, const FieldPath& path) const;

  using Type = IdlType;
  using Member = IdlMember;

 private:
  IdlStructs structs_;  // by name, qualified and bare
};

}  // namespace brickyard::cdr
