#pragma once
// The MCAP container's byte layout (https://mcap.dev/spec, major version 0), shared by the writer
// and the reader: record opcodes, the magic, and little-endian field packing. Every record is
// <opcode u8><content length u64><content>; strings and byte fields carry a u32 length (a chunk's
// records a u64 one), maps a u32 byte length before their entries.
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace brickyard::mcap {

inline constexpr unsigned char kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum class Op : std::uint8_t {
  Header = 0x01,
  Footer = 0x02,
  Schema = 0x03,
  Channel = 0x04,
  Message = 0x05,
  Chunk = 0x06,
  MessageIndex = 0x07,
  ChunkIndex = 0x08,
  Attachment = 0x09,
  AttachmentIndex = 0x0A,
  Statistics = 0x0B,
  Metadata = 0x0C,
  MetadataIndex = 0x0D,
  SummaryOffset = 0x0E,
  DataEnd = 0x0F,
};

// Appends fields to a record's content.
struct Packer {
  std::string& out;
  template <typename T>
  void num(T v) {  // the host is little-endian (x86-64, aarch64), as MCAP is
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(b, sizeof(T));
  }
  void str(std::string_view s) {
    num(static_cast<std::uint32_t>(s.size()));
    out.append(s.data(), s.size());
  }
};

// Reads fields from a record's content; `ok` turns false (and stays) on reading past its end.
struct Unpacker {
  const unsigned char* p;
  std::size_t n;
  std::size_t at = 0;
  bool ok = true;
  template <typename T>
  T num() {
    T v{};
    if (!ok || n - at < sizeof(T)) {
      ok = false;
      return v;
    }
    std::memcpy(&v, p + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  std::string_view bytes(std::uint64_t len) {
    if (!ok || n - at < len) {
      ok = false;
      return {};
    }
    std::string_view v(reinterpret_cast<const char*>(p + at), static_cast<std::size_t>(len));
    at += static_cast<std::size_t>(len);
    return v;
  }
  std::string_view str() { return bytes(num<std::uint32_t>()); }
};

}  // namespace brickyard::mcap
