#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "ugv/nodscan/scan_assembler.hpp"

using namespace ugv::nodscan;
using Catch::Detail::Approx;

namespace {
ScanView view(const std::vector<float>& ranges, int64_t utime, double angle_min, double angle_inc, double time_inc)
{
    ScanView s;
    s.utime = utime;
    s.angle_min = angle_min;
    s.angle_increment = angle_inc;
    s.time_increment = time_inc;
    s.range_max = 80.0;
    s.ranges = ranges.data();
    s.n = ranges.size();
    return s;
}
}  // namespace

TEST_CASE("Flat ground: every beam of a laser tilted down by t at height h lands at z = 0")
{
    const double h = 0.87, t = 0.3;
    AssemblerConfig cfg;
    cfg.mount.axis_xyz_m = {0.2, 0.0, h};
    ScanAssembler a(cfg);
    ServoHistory servo;
    servo.add({0, t});
    servo.add({1'000'000, t});
    const double amin = -std::numbers::pi / 2, inc = std::numbers::pi / 360;  // 181 x 0.5 deg
    std::vector<float> ranges;
    for (int i = 0; i < 361; ++i) {
        const double ang = amin + inc * i;
        const double c = std::cos(ang);
        ranges.push_back(c > 0.1 ? static_cast<float>(h / (std::sin(t) * c)) : NAN);
    }
    PointCloud pc;
    const auto st = a.assemble(view(ranges, 100'000, amin, inc, 1e-5), servo, pc);
    CHECK(st.points + st.dropped_invalid == 361);
    CHECK(st.dropped_invalid > 0);
    CHECK(st.dropped_no_angle == 0);
    REQUIRE(pc.size() == st.points);
    for (std::size_t i = 0; i < pc.size(); ++i) REQUIRE(pc.z[i] == Approx(0.0).margin(1e-5));
    // The centre beam (index 180) is straight ahead at h / tan(t).
    CHECK(pc.y[pc.size() / 2] == Approx(0.0).margin(1e-5));
    CHECK(pc.x[pc.size() / 2] == Approx(0.2 + h / std::tan(t)).epsilon(1e-6));
    CHECK(pc.sensor_origin[2] == Approx(h));
    CHECK(pc.utime == 100'000);
}

TEST_CASE("Each beam uses the tilt at its own time")
{
    // The tilt ramps 0 -> 0.2 rad over 20 ms; 101 forward beams over the same 20 ms, 1 m each.
    AssemblerConfig cfg;
    cfg.mount.axis_xyz_m = {0.0, 0.0, 1.0};
    ScanAssembler a(cfg);
    ServoHistory servo;
    servo.add({1'000'000, 0.0});
    servo.add({1'010'000, 0.1});
    servo.add({1'020'000, 0.2});
    std::vector<float> ranges(101, 1.0f);
    PointCloud pc;
    const auto st = a.assemble(view(ranges, 1'000'000, 0.0, 0.0, 0.0002), servo, pc);
    REQUIRE(st.points == 101);
    for (std::size_t i = 0; i < 101; ++i) {
        const double tilt = 0.2 * static_cast<double>(i) / 100.0;
        CHECK(pc.z[i] == Approx(1.0 - std::sin(tilt)).margin(1e-6));
        CHECK(pc.x[i] == Approx(std::cos(tilt)).margin(1e-6));
        CHECK(pc.time_offset[i] == Approx(0.0002 * static_cast<double>(i)));
    }
}

TEST_CASE("Interlaced sweeps: each beam uses the tilt of the sweep that measured it")
{
    // Tilt ramps 0 -> 0.4 rad over 40 ms. 9 forward beams measured in 2 sweeps 20 ms apart,
    // odd beams first: beam i at 1 ms x i + 20 ms if i is even.
    AssemblerConfig cfg;
    cfg.mount.axis_xyz_m = {0.0, 0.0, 1.0};
    ScanAssembler a(cfg);
    ServoHistory servo;
    servo.add({1'000'000, 0.0});
    servo.add({1'040'000, 0.4});
    std::vector<float> ranges(9, 1.0f);
    ScanView v = view(ranges, 1'000'000, 0.0, 0.0, 0.001);
    const int8_t odd_first[2] = {1, 0};
    REQUIRE(v.set_sweeps(odd_first, 2, 0.020));
    PointCloud pc;
    REQUIRE(a.assemble(v, servo, pc).points == 9);
    for (std::size_t i = 0; i < 9; ++i) {
        const double t = 0.001 * static_cast<double>(i) + (i % 2 == 0 ? 0.020 : 0.0);
        CHECK(pc.time_offset[i] == Approx(t));
        CHECK(pc.z[i] == Approx(1.0 - std::sin(10.0 * t)).margin(1e-6));
    }
    // The last beam measured is beam 8, in the second sweep.
    CHECK(ScanAssembler::last_beam_utime(v) == 1'028'000);
    // Layouts that are not one are refused, leaving the view as it was.
    const int8_t twice[2] = {0, 0};
    const int8_t out_of_range[2] = {0, 2};
    CHECK_FALSE(v.set_sweeps(twice, 2, 0.02));
    CHECK_FALSE(v.set_sweeps(out_of_range, 2, 0.02));
    CHECK_FALSE(v.set_sweeps(odd_first, 2, NAN));
    CHECK_FALSE(v.set_sweeps(odd_first, 0, 0.02));
    CHECK(v.sweeps == 2);
    CHECK(v.sweep_of_phase[0] == 1);
}

TEST_CASE("Invalid ranges and beams without a servo angle are dropped and counted")
{
    AssemblerConfig cfg;
    cfg.max_extrapolation_us = 1'000;
    ScanAssembler a(cfg);
    ServoHistory servo;
    servo.add({0, 0.1});
    servo.add({5'000, 0.1});
    // 10 beams 1 ms apart: beams 0..6 are within the history + 1 ms of extrapolation.
    std::vector<float> ranges = {1.0f, NAN, 2.0f, -1.0f, 0.0f, 100.0f, 3.0f, 4.0f, 5.0f, NAN};
    PointCloud pc;
    const auto st = a.assemble(view(ranges, 0, 0.0, 0.01, 0.001), servo, pc);
    CHECK(st.dropped_invalid == 5);   // NaN, -1, 0, beyond range_max 80 m, NaN
    CHECK(st.dropped_no_angle == 2);  // beams 7 and 8
    CHECK(st.points == 3);
    REQUIRE(pc.size() == 3);
    CHECK(pc.range[0] == 1.0f);
    CHECK(pc.range[1] == 2.0f);
    CHECK(pc.range[2] == 3.0f);
    CHECK(ScanAssembler::last_beam_utime(view(ranges, 0, 0.0, 0.01, 0.001)) == 9'000);
}

TEST_CASE("Per-point variance: range noise plus encoder angle noise times range")
{
    AssemblerConfig cfg;
    cfg.range_sigma_m = 0.01;
    cfg.angle_sigma_rad = 0.001;
    ScanAssembler a(cfg);
    ServoHistory servo;
    servo.add({0, 0.0});
    servo.add({1'000, 0.0});
    std::vector<float> ranges = {10.0f, 1.0f};
    PointCloud pc;
    a.assemble(view(ranges, 0, 0.0, 0.0, 0.0), servo, pc);
    REQUIRE(pc.size() == 2);
    CHECK(pc.variance[0] == Approx(1e-4 + 1e-4));
    CHECK(pc.variance[1] == Approx(1e-4 + 1e-6));
}

TEST_CASE("The fast path equals the reference transform for an arbitrary mount")
{
    AssemblerConfig cfg;
    cfg.mount.axis_xyz_m = {0.3, -0.1, 1.2};
    cfg.mount.axis_rpy_rad = {0.02, -0.05, 0.1};
    cfg.mount.laser_xyz_m = {0.08, 0.01, 0.06};
    cfg.mount.laser_rpy_rad = {0.01, 0.03, -0.02};
    ScanAssembler a(cfg);
    ServoHistory servo;
    servo.add({0, 0.35});
    servo.add({1'000, 0.35});
    std::vector<float> ranges = {3.0f, 7.5f, 12.25f};
    PointCloud pc;
    a.assemble(view(ranges, 0, -0.4, 0.4, 0.0), servo, pc);
    REQUIRE(pc.size() == 3);
    for (std::size_t i = 0; i < 3; ++i) {
        const Eigen::Vector3d p = beam_point_body(cfg.mount, 0.35, -0.4 + 0.4 * static_cast<double>(i), ranges[i]);
        CHECK(pc.x[i] == Approx(p[0]).margin(1e-5));
        CHECK(pc.y[i] == Approx(p[1]).margin(1e-5));
        CHECK(pc.z[i] == Approx(p[2]).margin(1e-5));
    }
}
