#include "cdr/ros2_pointcloud.hpp"

#include "cdr/cdr_reader.hpp"
#include "cdr/cdr_writer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace brickyard::cdr {

namespace {

// PointField's datatypes (sensor_msgs/msg/PointField) and their sizes.
enum Datatype : std::uint8_t { INT8 = 1, UINT8, INT16, UINT16, INT32, UINT32, FLOAT32, FLOAT64 };
std::size_t datatype_size(std::uint8_t t) {
  static const std::size_t sizes[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
  return t >= INT8 && t <= FLOAT64 ? sizes[t] : 0;
}

struct Field {
  std::string name;
  std::uint32_t offset = 0, count = 0;
  std::uint8_t datatype = 0;
};

// A numeric field's value of one point, as a double.
double value_of(const unsigned char* p, std::uint8_t t, bool little) {
  switch (t) {
    case INT8: return static_cast<std::int8_t>(*p);
    case UINT8: return *p;
    case INT16: { std::int16_t v; load(&v, p, 2, little); return v; }
    case UINT16: { std::uint16_t v; load(&v, p, 2, little); return v; }
    case INT32: { std::int32_t v; load(&v, p, 4, little); return v; }
    case UINT32: { std::uint32_t v; load(&v, p, 4, little); return v; }
    case FLOAT32: { float v; load(&v, p, 4, little); return v; }
    default: { double v; load(&v, p, 8, little); return v; }
  }
}

const Field* field_named(const std::vector<Field>& fields, std::initializer_list<const char*> names) {
  for (const char* n : names)
    for (const Field& f : fields)
      if (f.name == n) return &f;
  return nullptr;
}

std::vector<Field> read_fields(CdrReader& r) {
  // A field: its name's length, offset, datatype and count, 13 bytes at the least.
  std::vector<Field> fields(r.count("fields' count", 13));
  for (Field& f : fields) {
    f.name = r.string("a field's name");
    f.offset = r.get<std::uint32_t>("a field's offset");
    f.datatype = r.get<std::uint8_t>("a field's datatype");
    f.count = r.get<std::uint32_t>("a field's count");
  }
  return fields;
}

void check_fields(const std::vector<Field>& fields, std::uint32_t point_step) {
  for (const Field& f : fields) {
    const std::size_t size = datatype_size(f.datatype);
    if (size == 0) throw BadPointCloud2("PointCloud2: field '" + f.name + "' has datatype " + std::to_string(f.datatype) + ", none of 1 to 8");
    if (static_cast<std::size_t>(f.offset) + size * std::max<std::uint32_t>(f.count, 1) > point_step)
      throw BadPointCloud2("PointCloud2: field '" + f.name + "' (" + std::to_string(size) + " bytes at " + std::to_string(f.offset) +
                           ") is past the point step " + std::to_string(point_step));
  }
  for (const char* axis : {"x", "y", "z"}) {
    const Field* f = field_named(fields, {axis});
    if (!f) {
      std::string names;
      for (const Field& g : fields) names += (names.empty() ? "" : ", ") + g.name;
      throw BadPointCloud2(std::string("PointCloud2: no field '") + axis + "' (fields: " + (names.empty() ? "none" : names) + ")");
    }
    if (f->datatype != FLOAT32 && f->datatype != FLOAT64)
      throw BadPointCloud2(std::string("PointCloud2: field '") + axis + "' is not FLOAT32 or FLOAT64 (datatype " + std::to_string(f->datatype) + ")");
  }
}

}  // namespace

CloudColumns read_pointcloud2(const unsigned char* cdr, std::size_t size) {
  CloudColumns c;
  read_pointcloud2(cdr, size, c);
  return c;
}

void read_pointcloud2(const unsigned char* cdr, std::size_t size, CloudColumns& c) {
  CdrReader r(cdr, size, "PointCloud2");
  c.stamp_ns = r.time_ns("header.stamp");
  c.frame_id = r.string("header.frame_id");
  const auto height = r.get<std::uint32_t>("height"), width = r.get<std::uint32_t>("width");
  const std::vector<Field> fields = read_fields(r);
  const bool big = r.get<std::uint8_t>("is_bigendian") != 0;
  const auto point_step = r.get<std::uint32_t>("point_step"), row_step = r.get<std::uint32_t>("row_step");
  const auto [data, bytes] = r.bytes("data");
  check_fields(fields, point_step);
  const std::uint64_t points = static_cast<std::uint64_t>(height) * width;
  const std::string shape = "PointCloud2: " + std::to_string(height) + " x " + std::to_string(width) + " points of " + std::to_string(point_step) +
                            " bytes, rows of " + std::to_string(row_step);
  if (row_step < static_cast<std::uint64_t>(width) * point_step) throw BadPointCloud2(shape + ": a row shorter than its points");
  if (bytes < static_cast<std::uint64_t>(height) * row_step) throw DamagedSample(shape + ", in " + std::to_string(bytes) + " bytes of data");
  const Field *fx = field_named(fields, {"x"}), *fy = field_named(fields, {"y"}), *fz = field_named(fields, {"z"});
  const Field* fi = field_named(fields, {"intensity"});
  const Field* ft = field_named(fields, {"t", "time", "time_offset"});
  const bool little = !big;
  // Filled in place, each column as long as the points, then cut to those with a return.
  c.x.resize(points), c.y.resize(points), c.z.resize(points);
  c.intensity.resize(fi ? points : 0);
  c.time_offset.resize(ft ? points : 0);
  // No points (a width of 0): nothing to walk, however many empty rows it claims (found by
  // fuzz_ros2_sensors: 4 billion of them held a reader for minutes).
  const std::uint32_t rows = points == 0 ? 0 : height;
  const bool floats = little == host_little() && fx->datatype == FLOAT32 && fy->datatype == FLOAT32 && fz->datatype == FLOAT32 &&
                      (!fi || fi->datatype == FLOAT32) && (!ft || ft->datatype == FLOAT32);
  std::size_t k = 0;
  for (std::uint32_t row = 0; row < rows; ++row) {
    const unsigned char* p = data + static_cast<std::size_t>(row) * row_step;
    for (std::uint32_t col = 0; col < width; ++col, p += point_step) {
      float x, y, z;
      if (floats) {  // the common layout, read as it lies
        std::memcpy(&x, p + fx->offset, 4), std::memcpy(&y, p + fy->offset, 4), std::memcpy(&z, p + fz->offset, 4);
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
        if (fi) std::memcpy(&c.intensity[k], p + fi->offset, 4);
        if (ft) std::memcpy(&c.time_offset[k], p + ft->offset, 4);
      } else {
        x = static_cast<float>(value_of(p + fx->offset, fx->datatype, little));
        y = static_cast<float>(value_of(p + fy->offset, fy->datatype, little));
        z = static_cast<float>(value_of(p + fz->offset, fz->datatype, little));
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
        if (fi) c.intensity[k] = static_cast<float>(value_of(p + fi->offset, fi->datatype, little));
        if (ft) {
          const double t = value_of(p + ft->offset, ft->datatype, little);
          c.time_offset[k] = static_cast<float>(ft->datatype == FLOAT32 || ft->datatype == FLOAT64 ? t : t * 1e-9);
        }
      }
      c.x[k] = x, c.y[k] = y, c.z[k] = z;
      ++k;
    }
  }
  c.x.resize(k), c.y.resize(k), c.z.resize(k);
  if (fi) c.intensity.resize(k);
  if (ft) c.time_offset.resize(k);
}

std::vector<unsigned char> write_pointcloud2(const CloudColumns& c) {
  std::vector<unsigned char> out;
  write_pointcloud2(c, out);
  return out;
}

void write_pointcloud2(const CloudColumns& c, std::vector<unsigned char>& out) {
  const std::size_t n = c.x.size();
  const bool with_i = c.intensity.size() == n && n > 0, with_t = c.time_offset.size() == n && n > 0;
  std::vector<std::pair<std::string, const std::vector<float>*>> columns = {{"x", &c.x}, {"y", &c.y}, {"z", &c.z}};
  if (with_i) columns.emplace_back("intensity", &c.intensity);
  if (with_t) columns.emplace_back("t", &c.time_offset);
  const std::uint32_t step = static_cast<std::uint32_t>(4 * columns.size());
  CdrWriter w(out);
  out.reserve(256 + n * step);
  w.put_header(c.stamp_ns, c.frame_id);
  w.put<std::uint32_t>(1);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(n));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(columns.size()));
  for (std::size_t k = 0; k < columns.size(); ++k) {
    w.put_string(columns[k].first);
    w.put<std::uint32_t>(static_cast<std::uint32_t>(4 * k));
    w.put<std::uint8_t>(FLOAT32);
    w.put<std::uint32_t>(1);
  }
  w.put<std::uint8_t>(0);  // little-endian points
  w.put<std::uint32_t>(step);
  w.put<std::uint32_t>(static_cast<std::uint32_t>(n * step));
  w.put<std::uint32_t>(static_cast<std::uint32_t>(n * step));
  const std::size_t at = out.size();
  out.resize(at + n * step);
  unsigned char* p = out.data() + at;
  const bool as_is = host_little();  // little-endian floats are the host's own bytes
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const float* column = columns[k].second->data();
    unsigned char* q = p + 4 * k;
    for (std::size_t i = 0; i < n; ++i, q += step)
      if (as_is) std::memcpy(q, column + i, 4);
      else load(q, reinterpret_cast<const unsigned char*>(column + i), 4, true);
  }
  w.put<std::uint8_t>(1);  // is_dense
}

}  // namespace brickyard::cdr
