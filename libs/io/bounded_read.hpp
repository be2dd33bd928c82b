#pragma once
// A whole regular file read, bounded: a FIFO, a device (/dev/zero) or a folder is refused before
// a byte is read (a read of one would hang or grow without end), and so is a file larger than
// `max_bytes`. Returns false with `error` saying why ("PATH: not a regular file"). Header-only,
// framework-free, no exceptions.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace brickyard::io {

// Whether `path` is a regular file that can be opened, checked without blocking (a FIFO's open
// waits for a writer) before a stream reads it; else false with `error` saying why. For readers
// that stream a file rather than take it whole.
inline bool is_regular_readable(const std::string& path, std::string& error) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return error = path + ": cannot be opened (" + std::strerror(errno) + ")", false;
  struct stat st {};
  const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
  ::close(fd);
  if (!regular) error = path + ": not a regular file";
  return regular;
}

inline bool read_regular_file(const std::string& path, std::size_t max_bytes, std::vector<std::uint8_t>& out, std::string& error) {
  // Opened without blocking (a FIFO's open waits for a writer), then checked on the descriptor.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return error = path + ": cannot be opened (" + std::strerror(errno) + ")", false;
  struct stat st {};
  const bool regular = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode);
  if (!regular || static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    ::close(fd);
    error = path + (regular ? ": larger than " + std::to_string(max_bytes) + " bytes" : ": not a regular file");
    return false;
  }
  out.resize(static_cast<std::size_t>(st.st_size));
  std::size_t at = 0;
  while (at < out.size()) {
    const ssize_t n = ::read(fd, out.data() + at, out.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // shorter than fstat said (truncated meanwhile): what was read is kept
    at += static_cast<std::size_t>(n);
  }
  const int err = errno;
  ::close(fd);
  if (at < out.size() && at == 0 && !out.empty()) return error = path + ": cannot be read (" + std::strerror(err) + ")", false;
  out.resize(at);
  return true;
}

}  // namespace brickyard::io
