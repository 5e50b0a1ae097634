#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include <GeographicLib/Geodesic.hpp>

#include "ugv/estimation/local_frame.hpp"

using ugv::estimation::Datum;
using ugv::estimation::LocalFrame;

// DRDC Suffield, roughly.
const Datum kDatum{50.2700, -110.7400, 750.0};

TEST_CASE("the datum itself is the ENU origin")
{
    const LocalFrame f(kDatum);
    const Eigen::Vector3d o = f.to_enu(kDatum.latitude_deg, kDatum.longitude_deg, kDatum.height_m);
    CHECK(o.norm() < 1e-9);
}

TEST_CASE("ENU of a point agrees with GeographicLib's geodesic distance and azimuth")
{
    // An independent answer: the geodesic from the datum to a point a few hundred metres away
    // has a length and an azimuth (clockwise from north) that the local tangent plane must
    // reproduce at this distance (the plane departs from the ellipsoid by about d^2 / 2R).
    // On the ellipsoid (height 0): the geodesic is measured there, and at 750 m every
    // horizontal distance is (R + h) / R = 1.00012 times longer.
    const Datum on_ellipsoid{kDatum.latitude_deg, kDatum.longitude_deg, 0.0};
    const LocalFrame f(on_ellipsoid);
    const GeographicLib::Geodesic& g = GeographicLib::Geodesic::WGS84();
    for (const auto& [dlat, dlon] : {std::pair{0.002, 0.0}, std::pair{0.0, 0.003}, std::pair{-0.0015, 0.0025}}) {
        const double lat = kDatum.latitude_deg + dlat, lon = kDatum.longitude_deg + dlon;
        double s12 = 0, azi1 = 0, azi2 = 0;
        g.Inverse(kDatum.latitude_deg, kDatum.longitude_deg, lat, lon, s12, azi1, azi2);
        const Eigen::Vector3d enu = f.to_enu(lat, lon, 0.0);
        const double az_deg = std::atan2(enu.x(), enu.y()) * 180.0 / M_PI;
        CHECK(enu.head<2>().norm() == Approx(s12).epsilon(2e-6));
        CHECK(az_deg == Approx(azi1).margin(1e-3));
        // Earth curvature: the point sits below the tangent plane by about d^2 / (2 R).
        CHECK(enu.z() == Approx(-s12 * s12 / (2.0 * 6.37e6)).epsilon(0.02));
    }
}

TEST_CASE("0.001 deg of latitude at 50 deg N is 111.2 m north (WGS84 meridian arc)")
{
    const LocalFrame f(kDatum);
    const Eigen::Vector3d enu = f.to_enu(kDatum.latitude_deg + 0.001, kDatum.longitude_deg, kDatum.height_m);
    // Meridian radius of curvature at 50.27 deg: M = a(1-e2)/(1-e2 sin^2)^1.5 = 6373.0 km,
    // so 0.001 deg -> 111.23 m.
    CHECK(enu.y() == Approx(111.23).margin(0.02));
    CHECK(std::fabs(enu.x()) < 1e-6);
}

TEST_CASE("height is ellipsoidal: 10 m above the datum is 10 m up")
{
    const LocalFrame f(kDatum);
    CHECK(f.to_enu(kDatum.latitude_deg, kDatum.longitude_deg, kDatum.height_m + 10.0).z() == Approx(10.0));
}

TEST_CASE("to_geodetic inverts to_enu")
{
    const LocalFrame f(kDatum);
    const Eigen::Vector3d enu(123.4, -567.8, 9.1);
    const Eigen::Vector3d llh = f.to_geodetic(enu);
    CHECK((f.to_enu(llh.x(), llh.y(), llh.z()) - enu).norm() < 1e-6);
}

TEST_CASE("an impossible datum is refused")
{
    CHECK_THROWS_AS(LocalFrame(Datum{91.0, 0.0, 0.0}), std::invalid_argument);
    CHECK_THROWS_AS(LocalFrame(Datum{0.0, 181.0, 0.0}), std::invalid_argument);
    CHECK_THROWS_AS(LocalFrame(Datum{0.0, 0.0, NAN}), std::invalid_argument);
}
