#pragma once
// The point map as a PCD file (PCL's format, v0.7, binary x y z float), framework-free. Written
// whole or not at all: to a temporary beside it, then renamed.
#include "voxel_map.hpp"

#include <string>

namespace brickyard::mapping {

// Each voxel's mean point. Throws std::runtime_error naming the file when it cannot be written.
void write_pcd(const std::string& path, const VoxelMap& map);

// The points of a PCD file this writes (binary or ascii x y z float, in that order).
// Throws std::runtime_error naming the file and what is wrong.
Points read_pcd(const std::string& path);

}  // namespace brickyard::mapping
