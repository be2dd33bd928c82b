#include "local_datum.hpp"

#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>

namespace brickyard::drivers {

struct LocalDatum::Impl {
  GeographicLib::LocalCartesian frame;
};

LocalDatum::LocalDatum(const Datum& datum)
    : datum_(datum), impl_(std::make_unique<Impl>(Impl{GeographicLib::LocalCartesian(datum.latitude_deg, datum.longitude_deg, datum.height_m)})) {}
LocalDatum::~LocalDatum() = default;
LocalDatum::LocalDatum(LocalDatum&&) noexcept = default;
LocalDatum& LocalDatum::operator=(LocalDatum&&) noexcept = default;

Eigen::Vector3d LocalDatum::to_map(const Geodetic& g) const {
  Eigen::Vector3d enu;
  impl_->frame.Forward(g.latitude_deg, g.longitude_deg, g.height_m, enu.x(), enu.y(), enu.z());
  return enu;
}

Geodetic LocalDatum::to_geodetic(const Eigen::Vector3d& enu) const {
  Geodetic g;
  impl_->frame.Reverse(enu.x(), enu.y(), enu.z(), g.latitude_deg, g.longitude_deg, g.height_m);
  return g;
}

const char* datum_problem(const Datum& d) {
  if (!std::isfinite(d.latitude_deg) || std::abs(d.latitude_deg) > 90) return "latitude outside [-90, 90] deg";
  if (!std::isfinite(d.longitude_deg) || std::abs(d.longitude_deg) > 180) return "longitude outside [-180, 180] deg";
  if (!std::isfinite(d.height_m) || d.height_m < -1000 || d.height_m > 10000) return "height outside [-1000, 10000] m";
  return "";
}

}  // namespace brickyard::drivers
