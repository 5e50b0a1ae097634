// The local ENU frame of a datum (lat, lon, ellipsoidal height) through
// GeographicLib::LocalCartesian on the WGS84 ellipsoid.
#pragma once

#include <Eigen/Core>
#include <GeographicLib/LocalCartesian.hpp>

namespace ugv::estimation {

struct Datum
{
    double latitude_deg = 0.0;
    double longitude_deg = 0.0;
    double height_m = 0.0;  // ellipsoidal
};

class LocalFrame
{
public:
    // Throws std::invalid_argument for a latitude outside [-90, 90], a longitude outside
    // [-180, 180] or a non-finite value.
    explicit LocalFrame(const Datum& datum);

    const Datum& datum() const { return datum_; }
    // Geodetic -> ENU (m).
    Eigen::Vector3d to_enu(double latitude_deg, double longitude_deg, double height_m) const;
    // ENU (m) -> geodetic (lat deg, lon deg, ellipsoidal height m).
    Eigen::Vector3d to_geodetic(const Eigen::Vector3d& enu) const;

private:
    Datum datum_;
    GeographicLib::LocalCartesian projection_;
};

}  // namespace ugv::estimation
