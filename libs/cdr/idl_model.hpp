#pragma once
// Message definitions in OMG IDL, read: the subset Brickyard's messages use (modules, structs, the
// primitive types, string, sequence<T> and fixed arrays; bounds kept). CdrJson reads samples by
// it (cdr_json.hpp), and the ROS 2 message package is written from it (ros2_msgs.hpp). An IDL may
// be untrusted input (a recording's schema): every error is std::invalid_argument naming its line.
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace brickyard::cdr {

// A member's type: a primitive, a string, a struct (by name), or a sequence of / array of one.
struct IdlType {
  enum Kind { Primitive, String, Struct, Sequence, Array } kind = Primitive;
  std::string name;             // primitive or struct (bare) name
  std::size_t size = 0;         // primitive: bytes; array: length
  std::size_t bound = 0;        // sequence, string: its bound (0: none)
  std::shared_ptr<IdlType> of;  // sequence, array: the element
};
struct IdlMember {
  std::string name;
  IdlType type;
};
using IdlStructs = std::map<std::string, std::shared_ptr<std::vector<IdlMember>>>;

struct IdlModel {
  IdlStructs structs;                // by name, qualified ("brickyard::msgs::Imu") and bare ("Imu")
  std::vector<std::string> defined;  // the qualified names, in the order the text defines them
};

IdlModel parse_idl(const std::string& idl);

// A type's IDL text in the form the SDK's texts have (the type's file, then depth first what it
// includes, each block ending "}; };") as one self-contained text, as an MCAP schema ("omgidl")
// carries it: no #include lines, each definition once and before what uses it.
std::string self_contained_idl(const std::string& idl);

// "brickyard::msgs::Imu" -> "Imu".
std::string idl_bare_name(const std::string& name);

}  // namespace brickyard::cdr
