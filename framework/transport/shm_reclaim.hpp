#pragma once
// Fast DDS's shared-memory data segments left in /dev/shm by processes that died without closing
// them (SIGKILL, power loss): 16 MiB each, never removed by Fast DDS. A live segment's owner holds
// an exclusive flock on its lock file (`fastrtps_<id>_el`); one that can be locked, and is older
// than the moment it takes a new participant to lock it, belongs to no live process, and goes.
// Port files are not touched: a restarted process reopens its ports (Fast DDS reuses them), and a
// dead process's port may still be mapped by a peer that sends to it (docs/reliability.md).
#include <cstdint>
#include <string>
#include <vector>

namespace brickyard::fw {

struct ReclaimedSegments {
  std::vector<std::string> files;  // the segments removed
  std::uint64_t bytes = 0;
};

// `dir`: /dev/shm, or a folder a test plants files in. `min_age_s`: a lock file younger than this
// may be a live participant's between creating and locking it.
ReclaimedSegments reclaim_dead_segments(const std::string& dir = "/dev/shm", double min_age_s = 2.0);

}  // namespace brickyard::fw
