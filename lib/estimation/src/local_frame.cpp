#include "ugv/estimation/local_frame.hpp"

#include <cmath>
#include <stdexcept>

namespace ugv::estimation {

namespace {

const Datum& checked(const Datum& d)
{
    if (!std::isfinite(d.latitude_deg) || !std::isfinite(d.longitude_deg) || !std::isfinite(d.height_m)) {
        throw std::invalid_argument("datum has a non-finite value");
    }
    if (std::fabs(d.latitude_deg) > 90.0) {
        throw std::invalid_argument("datum latitude outside [-90, 90] deg");
    }
    if (std::fabs(d.longitude_deg) > 180.0) {
        throw std::invalid_argument("datum longitude outside [-180, 180] deg");
    }
    return d;
}

}  // namespace

LocalFrame::LocalFrame(const Datum& datum)
    : datum_(checked(datum)), projection_(datum.latitude_deg, datum.longitude_deg, datum.height_m)
{
}

Eigen::Vector3d LocalFrame::to_enu(double latitude_deg, double longitude_deg, double height_m) const
{
    Eigen::Vector3d enu;
    projection_.Forward(latitude_deg, longitude_deg, height_m, enu.x(), enu.y(), enu.z());
    return enu;
}

Eigen::Vector3d LocalFrame::to_geodetic(const Eigen::Vector3d& enu) const
{
    Eigen::Vector3d llh;
    projection_.Reverse(enu.x(), enu.y(), enu.z(), llh.x(), llh.y(), llh.z());
    return llh;
}

}  // namespace ugv::estimation
