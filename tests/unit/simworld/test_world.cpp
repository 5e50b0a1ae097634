#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/simworld/world.hpp"

using namespace ugv::simworld;

namespace {
Scenario flat_run()
{
    Scenario s;
    s.path.accel_mps2 = 1.0;
    s.path.segments.push_back({PathSegment::Kind::straight, 10.0, 0, 0, 2.0, 0});
    s.path.segments.push_back({PathSegment::Kind::arc, 0, 5.0, M_PI / 2, 1.0, 0});
    s.field_resolution_m = 0.05;
    s.field_margin_m = 15;
    return s;
}
constexpr int64_t kStart = 1'700'000'000'000'000;
}  // namespace

TEST_CASE("on flat ground the truth is level, moving along the path, with the centripetal acceleration in the turn")
{
    const World w(flat_run(), kStart);
    const TruthState s = w.truth(kStart + 4'000'000);  // cruising at 2 m/s
    CHECK(s.roll_rad == 0.0);
    CHECK(s.pitch_rad == 0.0);
    CHECK(s.position_m.z() == 0.0);
    CHECK(s.velocity_mps.x() == Approx(2.0));
    CHECK(s.accel_mps2.norm() == Approx(0.0).margin(1e-9));
    // In the arc at 1 m/s on a 5 m radius: v^2/r = 0.2 m/s^2 to the left (north while heading east).
    const TruthState t = w.truth(kStart + 10'000'000);
    CHECK(t.rate_body_radps.z() == Approx(0.2).margin(1e-6));
    const Eigen::Vector3d left = t.orientation * Eigen::Vector3d::UnitY();
    CHECK(t.accel_mps2.dot(left) == Approx(0.2).margin(1e-6));
    CHECK(w.end_utime() > kStart + 14'000'000);
}

TEST_CASE("a laser beam from the tilted mount hits the ground where the geometry says")
{
    const World w(flat_run(), kStart);
    const TruthState s = w.truth(kStart);
    // Tilt axis at 0.87 m, laser on the axis: a beam at angle 0 tilted 10 deg nose down.
    const double tilt = 10.0 * M_PI / 180.0;
    CHECK(w.beam_range_m(s, tilt, 0.0, 80.0) == Approx(0.87 / std::sin(tilt)).epsilon(1e-9));
    // A beam 60 deg to the side: the scan plane is tilted, so the drop per metre is smaller.
    const double a = 60.0 * M_PI / 180.0;
    CHECK(w.beam_range_m(s, tilt, a, 80.0) == Approx(0.87 / (std::sin(tilt) * std::cos(a))).epsilon(1e-9));
    // Tilted up: no echo.
    CHECK(std::isinf(w.beam_range_m(s, -tilt, 0.0, 80.0)));
}

TEST_CASE("each laser of a scenario casts from its own mount")
{
    Scenario sc = flat_run();
    LaserSpec high;
    high.name = "high";
    high.mount.axis_xyz_m = {0.0, 0.5, 1.5};
    sc.lasers.push_back(high);
    const World w(sc, kStart);
    const TruthState s = w.truth(kStart);
    const double tilt = 10.0 * M_PI / 180.0;
    CHECK(w.beam_range_m(s, tilt, 0.0, 80.0, 0) == Approx(0.87 / std::sin(tilt)).epsilon(1e-9));
    CHECK(w.beam_range_m(s, tilt, 0.0, 80.0, 1) == Approx(1.5 / std::sin(tilt)).epsilon(1e-9));
}

TEST_CASE("a ramp pitches the vehicle nose up, and the antenna's position is geodetic")
{
    Scenario sc = flat_run();
    sc.terrain.ramps.push_back({{3.0, -5.0, 13.0, 5.0}, 1.0, Direction::east});  // 10 % slope
    const World w(sc, kStart);
    const TruthState s = w.truth(kStart + 5'000'000);  // x = 2 + 2*3 = 8 m: all wheels on the ramp
    CHECK(s.position_m.x() == Approx(8.0).margin(0.01));
    CHECK(s.pitch_rad == Approx(-std::atan(0.1)).margin(0.01));  // nose up is negative
    CHECK(s.position_m.z() == Approx(0.5).margin(0.01));
    const Geodetic g = w.antenna_position(s);
    const Geodetic datum = w.to_geodetic(Eigen::Vector3d::Zero());
    CHECK(datum.latitude_deg == Approx(sc.datum_latitude_deg));
    CHECK(g.longitude_deg > datum.longitude_deg);  // east of the datum
    CHECK(g.height_m == Approx(sc.datum_height_m + 0.5 + 1.8).margin(0.2));
}

TEST_CASE("the antenna's velocity in a turn is the reference point's plus yaw rate x lever arm")
{
    Scenario sc = flat_run();
    sc.gps.antenna_m = {0.4, -0.1, 1.8};
    const World w(sc, kStart);
    // In the arc at 1 m/s on a 5 m radius (0.2 rad/s): in the body frame (v - w y, w x).
    const TruthState t = w.truth(kStart + 10'000'000);
    const Eigen::Vector3d body = t.orientation.conjugate() * w.antenna_velocity(t);
    CHECK(body.x() == Approx(1.0 + 0.2 * 0.1).margin(1e-6));
    CHECK(body.y() == Approx(0.2 * 0.4).margin(1e-6));
    CHECK(body.z() == Approx(0.0).margin(1e-9));
    // Straight: the reference point's.
    const TruthState s = w.truth(kStart + 4'000'000);
    CHECK((w.antenna_velocity(s) - s.velocity_mps).norm() < 1e-12);
}
