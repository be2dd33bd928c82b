// libFuzzer harness: a ROS 2 bag's sensor message (the first byte picks PointCloud2, NavSatFix,
// Imu or Odometry; then its CDR) through the readers bag play --map and replay.ros2_* use
// (cdr/ros2_*.hpp). Bad bytes must end in DamagedSample or a named invalid_argument, never a
// crash; a cloud read whole is written back and read again to the same points, an odometry
// written back and read again to the same bytes.
#include "cdr/cdr_reader.hpp"
#include "cdr/ros2_pointcloud.hpp"
#include "cdr/ros2_sensors.hpp"
#include "cdr/ros2_state_msgs.hpp"

#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  const unsigned char* cdr = data + 1;
  const std::size_t n = size - 1;
  try {
    switch (data[0] % 4) {
      case 0: {
        const auto c = brickyard::cdr::read_pointcloud2(cdr, n);
        const auto again = brickyard::cdr::write_pointcloud2(c);
        const auto back = brickyard::cdr::read_pointcloud2(again.data(), again.size());
        if (back.x != c.x || back.y != c.y || back.z != c.z) std::abort();  // a cloud read is written back whole
        break;
      }
      case 1: (void)brickyard::cdr::read_navsatfix(cdr, n); break;
      case 2: (void)brickyard::cdr::read_imu(cdr, n); break;
      default: {
        std::vector<unsigned char> once, twice;
        brickyard::cdr::write_odometry(brickyard::cdr::read_odometry(cdr, n), once);
        brickyard::cdr::write_odometry(brickyard::cdr::read_odometry(once.data(), once.size()), twice);
        if (once != twice) std::abort();  // what is read is written back the same
        break;
      }
    }
  } catch (const std::invalid_argument&) {  // DamagedSample, BadPointCloud2: named refusals
  }
  return 0;
}
