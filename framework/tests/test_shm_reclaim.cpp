// Dead processes' shared-memory segments reclaimed (transport/shm_reclaim.hpp), on files planted
// in a folder of the test's own: a segment whose lock file no one holds goes, one that is held or
// just made stays, and ports are never touched.
#include "transport/shm_reclaim.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using brickyard::fw::reclaim_dead_segments;

namespace {

// A file of `bytes` bytes, last written `age_s` seconds ago.
void plant(const fs::path& p, std::size_t bytes, double age_s) {
  std::ofstream(p) << std::string(bytes, 'x');
  timespec now{};
  clock_gettime(CLOCK_REALTIME, &now);
  const timespec then{now.tv_sec - static_cast<time_t>(age_s), now.tv_nsec};
  const timespec times[2] = {then, then};
  ASSERT_EQ(utimensat(AT_FDCWD, p.c_str(), times, 0), 0);
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("brickyard_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

}  // namespace

TEST(ShmReclaim, ADeadSegmentGoesALiveOneStays) {
  const fs::path d = fresh_dir("shm_reclaim");
  plant(d / "fastrtps_00112233aabbccdd", 1000, 60);  // dead: its lock file held by no one
  plant(d / "fastrtps_00112233aabbccdd_el", 0, 60);
  plant(d / "fastrtps_ffeeddcc00000001", 2000, 60);  // live: its owner holds the lock
  plant(d / "fastrtps_ffeeddcc00000001_el", 0, 60);
  plant(d / "fastrtps_0123456789abcdef", 3000, 0);  // just made: not locked yet by its owner
  plant(d / "fastrtps_0123456789abcdef_el", 0, 0);
  plant(d / "fastrtps_port7411", 500, 60);  // a port: never touched
  plant(d / "fastrtps_port7411_el", 0, 60);
  plant(d / "fastrtps_aaaaaaaaaaaaaaaa", 700, 60);  // no lock file: not ours to judge
  const int owner = ::open((d / "fastrtps_ffeeddcc00000001_el").c_str(), O_RDWR);
  ASSERT_GE(owner, 0);
  ASSERT_EQ(::flock(owner, LOCK_EX | LOCK_NB), 0);

  const auto r = reclaim_dead_segments(d.string(), 2.0);
  ::close(owner);
  ASSERT_EQ(r.files.size(), 1u);
  EXPECT_EQ(r.files[0], (d / "fastrtps_00112233aabbccdd").string());
  EXPECT_EQ(r.bytes, 1000u);
  EXPECT_FALSE(fs::exists(d / "fastrtps_00112233aabbccdd"));
  EXPECT_FALSE(fs::exists(d / "fastrtps_00112233aabbccdd_el"));
  for (const char* kept : {"fastrtps_ffeeddcc00000001", "fastrtps_ffeeddcc00000001_el", "fastrtps_0123456789abcdef",
                           "fastrtps_port7411", "fastrtps_port7411_el", "fastrtps_aaaaaaaaaaaaaaaa"})
    EXPECT_TRUE(fs::exists(d / kept)) << kept;
  fs::remove_all(d);
}

TEST(ShmReclaim, AMissingFolderReclaimsNothing) {
  EXPECT_TRUE(reclaim_dead_segments("/nonexistent/brickyard/shm").files.empty());
}
