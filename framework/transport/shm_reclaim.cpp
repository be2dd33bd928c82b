#include "transport/shm_reclaim.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <ctime>

namespace brickyard::fw {
namespace {

// "fastrtps_" and sixteen hex digits: a data segment (ports are "fastrtps_port<N>").
bool is_segment_name(const std::string& name) {
  constexpr const char* kPrefix = "fastrtps_";
  if (name.size() != 9 + 16 || name.compare(0, 9, kPrefix) != 0) return false;
  for (std::size_t i = 9; i < name.size(); ++i)
    if (!std::isxdigit(static_cast<unsigned char>(name[i]))) return false;
  return true;
}

double age_s(const struct stat& st) {
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  return static_cast<double>(now.tv_sec - st.st_mtim.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec - st.st_mtim.tv_nsec);
}

// The segment `name` removed when its lock file can be locked (no live owner); its size if so.
bool remove_if_dead(const std::string& dir, const std::string& name, double min_age_s, std::uint64_t& bytes) {
  const std::string segment = dir + "/" + name, lock = segment + "_el";
  const int fd = ::open(lock.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK);
  if (fd < 0) return false;  // no lock file: not ours to judge
  struct stat st {};
  const bool old_enough = ::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && age_s(st) >= min_age_s;
  bool removed = false;
  if (old_enough && ::flock(fd, LOCK_EX | LOCK_NB) == 0) {  // held: its owner is gone
    struct stat seg {};
    if (::stat(segment.c_str(), &seg) == 0 && S_ISREG(seg.st_mode) && ::unlink(segment.c_str()) == 0) {
      bytes += static_cast<std::uint64_t>(seg.st_size);
      removed = true;
    }
    ::unlink(lock.c_str());  // while still locked: no one can take it meanwhile
  }
  ::close(fd);
  return removed;
}

}  // namespace

ReclaimedSegments reclaim_dead_segments(const std::string& dir, double min_age_s) {
  ReclaimedSegments out;
  DIR* d = ::opendir(dir.c_str());
  if (!d) return out;
  std::vector<std::string> names;
  while (const dirent* e = ::readdir(d))
    if (is_segment_name(e->d_name)) names.emplace_back(e->d_name);
  ::closedir(d);
  for (const auto& n : names)
    if (remove_if_dead(dir, n, min_age_s, out.bytes)) out.files.push_back(dir + "/" + n);
  return out;
}

}  // namespace brickyard::fw
