#pragma once
// Latitude, longitude and height to the map frame and back, framework-free. The map frame is the
// local east-north-up frame at a datum point (a graph parameter: the track's origin surveyed on
// WGS84): x east, y north, z up, metres, as GeographicLib's LocalCartesian gives it (the WGS84
// ellipsoid; exact, not a flat-earth approximation: over a 5 km track the two differ by
// centimetres, docs/drivers-formats.md). Heights are ellipsoidal: a receiver's height above mean
// sea level plus its undulation.
#include <Eigen/Core>

#include <memory>

namespace brickyard::drivers {

struct Datum {
  double latitude_deg = 0;
  double longitude_deg = 0;
  double height_m = 0;  // above the WGS84 ellipsoid
};

struct Geodetic {
  double latitude_deg = 0, longitude_deg = 0, height_m = 0;  // height above the WGS84 ellipsoid
};

class LocalDatum {
 public:
  explicit LocalDatum(const Datum& datum);
  ~LocalDatum();
  LocalDatum(LocalDatum&&) noexcept;
  LocalDatum& operator=(LocalDatum&&) noexcept;

  const Datum& datum() const { return datum_; }
  // East, north, up of a point, m.
  Eigen::Vector3d to_map(const Geodetic& g) const;
  Geodetic to_geodetic(const Eigen::Vector3d& enu) const;

 private:
  struct Impl;  // GeographicLib stays out of the header
  Datum datum_;
  std::unique_ptr<Impl> impl_;
};

// A datum a receiver could be at: latitude within [-90, 90], longitude within [-180, 180], height
// within [-1000, 10000] m, all finite. Empty when good, else what is wrong.
const char* datum_problem(const Datum& d);

}  // namespace brickyard::drivers
