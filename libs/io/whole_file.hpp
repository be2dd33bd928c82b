#pragma once
// A file written whole or not at all (issue 20): the bytes go to PATH.part, are flushed and
// checked, and renamed over PATH, so a reader never sees half a file and a full disk leaves the
// old one. A PATH that exists and is not a regular file (/dev/stdout, a pipe, /dev/full) is
// written in place — a rename would replace the device — its errors checked all the same.
// Throws WriteError "PATH: cannot be written (why)". Header-only, framework-free.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <sys/stat.h>

namespace brickyard::io {

// An output that could not be written (a full disk, a read-only folder): not bad input.
struct WriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline void write_whole_file(const std::string& path, const std::string& bytes) {
  struct stat st {};
  const bool in_place = ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
  const std::string target = in_place ? path : path + ".part";
  auto fail = [&](int err) {
    if (!in_place) std::remove(target.c_str());
    throw WriteError(path + ": cannot be written (" + std::strerror(err) + ")");
  };
  std::FILE* f = std::fopen(target.c_str(), "wb");
  if (!f) fail(errno);
  const bool wrote = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size() && std::fflush(f) == 0;
  const int err = errno;
  if (std::fclose(f) != 0 || !wrote) fail(wrote ? errno : err);
  if (!in_place && std::rename(target.c_str(), path.c_str()) != 0) fail(errno);
}

}  // namespace brickyard::io
