#pragma once
// Every message type of the SDK with its IDL decoder, in the order the build lists them: the
// harnesses that take a type's sample pick one by their input's first byte.
#include "cdr/cdr_json.hpp"
#include "record/recorder.hpp"  // omgidl_schema

#include <cstddef>
#include <memory>
#include <vector>

namespace fuzzing {

struct MessageType {
  const char* name;
  std::unique_ptr<brickyard::cdr::CdrJson> idl;
};

inline const std::vector<MessageType>& message_types() {
  struct IdlText {
    const char* type;
    const char* text;
  };
  static const IdlText kIdl[] = {
#include "idl_texts.inc"
  };
  static const std::vector<MessageType> types = [] {
    std::vector<MessageType> v;
    for (const auto& t : kIdl) v.push_back({t.type, std::make_unique<brickyard::cdr::CdrJson>(brickyard::fw::omgidl_schema(t.text))});
    return v;
  }();
  return types;
}

}  // namespace fuzzing
