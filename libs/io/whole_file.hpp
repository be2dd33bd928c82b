#pragma once
// A file written whole or not at all: the bytes go to PATH.part, are written, synced
// and checked, and renamed over PATH, so a reader never sees half a file and a full disk leaves
// the old one. A PATH that exists and is not a regular file (/dev/stdout, a pipe, /dev/full) is
// written in place — a rename would replace the device — its errors checked all the same.
// `mode`: the new file's permissions (0600 for a key: set before a byte of it is written).
// Throws WriteError "PATH: cannot be written (why)". Header-only, framework-free.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

namespace brickyard::io {

// An output that could not be written (a full disk, a read-only folder): not bad input.
struct WriteError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline void write_whole_file(const std::string& path, const std::string& bytes, mode_t mode = 0644) {
  struct stat st {};
  const bool in_place = ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
  const std::string target = in_place ? path : path + ".part";
  auto fail = [&](int err) {
    if (!in_place) ::unlink(target.c_str());
    throw WriteError(path + ": cannot be written (" + std::strerror(err) + ")");
  };
  if (!in_place) ::unlink(target.c_str());  // a stale part, perhaps of other permissions
  const int fd = in_place ? ::open(target.c_str(), O_WRONLY | O_CLOEXEC) : ::open(target.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
  if (fd < 0) fail(errno);
  std::size_t at = 0;
  while (at < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      ::close(fd);
      fail(err);
    }
    at += static_cast<std::size_t>(n);
  }
  if (!in_place && ::fsync(fd) != 0) {
    const int err = errno;
    ::close(fd);
    fail(err);
  }
  if (::close(fd) != 0) fail(errno);
  if (!in_place && std::rename(target.c_str(), path.c_str()) != 0) fail(errno);
}

}  // namespace brickyard::io
