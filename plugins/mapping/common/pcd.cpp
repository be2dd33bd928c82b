#include "pcd.hpp"

#include "io/bounded_read.hpp"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace brickyard::mapping {

void write_pcd(const std::string& path, const VoxelMap& map) {
  const std::string tmp = path + ".part";
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error(path + ": cannot write the map (" + tmp + " would not open)");
    const std::size_t n = map.size();
    f << "# .PCD v0.7 - Point Cloud Data file format\n"
      << "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
      << "WIDTH " << n << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA binary\n";
    for (const Voxel& v : map.voxels()) {
      const Eigen::Vector3f q = v.mean().cast<float>();
      f.write(reinterpret_cast<const char*>(q.data()), 3 * sizeof(float));
    }
    f.flush();
    if (!f) {
      f.close();
      std::remove(tmp.c_str());
      throw std::runtime_error(path + ": writing the map failed (disk full?)");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(path + ": cannot write the map (rename from " + tmp + " failed)");
  }
}

Points read_pcd(const std::string& path) {
  std::string error;
  if (!io::is_regular_readable(path, error)) throw std::runtime_error(error);  // a FIFO would hang the read
  std::ifstream f(path, std::ios::binary);
  if (!f) throw std::runtime_error(path + ": cannot open");
  std::string line, fields, data;
  std::size_t points = 0;
  bool have_points = false;
  int lines = 0;
  while (data.empty() && std::getline(f, line)) {
    if (++lines > 64) throw std::runtime_error(path + ": no DATA line in the header");
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string key;
    s >> key;
    if (key == "FIELDS") std::getline(s, fields);
    else if (key == "POINTS") have_points = static_cast<bool>(s >> points);
    else if (key == "DATA") s >> data;
  }
  if (fields != " x y z") throw std::runtime_error(path + ": FIELDS must be 'x y z', found '" + fields + "'");
  if (!have_points || points > (1u << 28)) throw std::runtime_error(path + ": POINTS missing or absurd");
  Points out(points);
  if (data == "binary") {
    for (std::size_t i = 0; i < points; ++i)
      if (!f.read(reinterpret_cast<char*>(out[i].data()), 3 * sizeof(float)))
        throw std::runtime_error(path + ": " + std::to_string(points) + " points declared, " + std::to_string(i) + " present");
  } else if (data == "ascii") {
    for (std::size_t i = 0; i < points; ++i)
      if (!(f >> out[i].x() >> out[i].y() >> out[i].z()))
        throw std::runtime_error(path + ": point " + std::to_string(i + 1) + " of " + std::to_string(points) + " is not three numbers");
  } else {
    throw std::runtime_error(path + ": DATA '" + data + "' not read (binary or ascii)");
  }
  return out;
}

}  // namespace brickyard::mapping
