#pragma once
// What the harnesses share: the input as a file, for the readers that take a path (the road
// graph, MCAP). One file per process, rewritten for each input: libFuzzer runs inputs one after
// another in a process.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace brickyard::fuzz {

inline std::string as_file(const std::uint8_t* data, std::size_t size, const char* suffix) {
  const std::string path = "/tmp/brickyard_fuzz_" + std::to_string(::getpid()) + suffix;
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  return path;
}

}  // namespace brickyard::fuzz
