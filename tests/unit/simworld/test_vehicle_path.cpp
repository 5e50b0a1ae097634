#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/simworld/vehicle_path.hpp"

using namespace ugv::simworld;

TEST_CASE("a straight run accelerates, cruises and brakes at the set acceleration")
{
    PathSpec spec;
    spec.accel_mps2 = 1.0;
    spec.segments.push_back({PathSegment::Kind::straight, 20.0, 0, 0, 2.0, 0});
    const VehiclePath path(spec);
    // 20 m, then braking from 2 m/s at 1 m/s^2 adds 2 m.
    CHECK(path.length_m() == Approx(22.0).margin(0.01));
    CHECK(path.at(1.0).speed_mps == Approx(1.0).margin(1e-3));
    CHECK(path.at(1.0).x_m == Approx(0.5).margin(1e-3));
    CHECK(path.at(5.0).speed_mps == Approx(2.0));
    CHECK(path.at(0.5).accel_along_mps2 == Approx(1.0));
    CHECK(path.at(5.0).accel_along_mps2 == Approx(0.0));
    const PlanarState end = path.at(path.duration_s());
    CHECK(end.speed_mps == 0.0);
    CHECK(end.x_m == Approx(22.0).margin(0.01));
    CHECK(end.y_m == 0.0);
    CHECK(path.duration_s() == Approx(2.0 + 18.0 / 2.0 + 2.0).margin(0.01));
}

TEST_CASE("a left arc of 90 degrees ends a radius ahead and a radius to the left, facing left")
{
    PathSpec spec;
    spec.x0_m = 5.0;
    spec.yaw0_rad = M_PI / 2;  // north
    spec.accel_mps2 = 1000.0;  // (almost) no braking distance
    spec.segments.push_back({PathSegment::Kind::arc, 0, 10.0, M_PI / 2, 2.0, 0});
    const VehiclePath path(spec);
    const PlanarState end = path.at(path.duration_s());
    CHECK(end.x_m == Approx(-5.0).margin(0.01));
    CHECK(end.y_m == Approx(10.0).margin(0.01));
    CHECK(std::cos(end.yaw_rad) == Approx(-1.0).margin(1e-6));
    const PlanarState mid = path.at(path.duration_s() / 2);
    CHECK(mid.yaw_rate_radps == Approx(2.0 / 10.0).margin(1e-6));
}

TEST_CASE("a stop stands for its duration")
{
    PathSpec spec;
    spec.segments.push_back({PathSegment::Kind::stop, 0, 0, 0, 0, 3.0});
    spec.segments.push_back({PathSegment::Kind::straight, 1.0, 0, 0, 1.0, 0});
    const VehiclePath path(spec);
    CHECK(path.at(2.9).x_m == 0.0);
    CHECK(path.at(3.5).x_m > 0.1);
}
