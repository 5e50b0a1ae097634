#include <catch2/catch.hpp>

#include <limits>

#include "nod_controller.hpp"

using namespace ugv;

TEST_CASE("Nod controller: a refused command leaves the running profile alone")
{
    servo_daemon::NodControllerOptions o;
    o.hard_limits = {-0.1, 0.6};
    o.lead_s = 0.05;
    servo_daemon::NodController nod(o);
    nodscan::NodCommand rate;
    rate.kind = nodscan::NodKind::constant_rate;
    rate.min_tilt_rad = 0.0;
    rate.max_tilt_rad = 0.5;
    rate.rate_rad_s = 1.0;
    REQUIRE_FALSE(nod.apply(rate, 0.0, 0.0));
    nodscan::NodCommand hold;
    hold.kind = nodscan::NodKind::hold;
    hold.hold_angle_rad = 0.7;  // beyond the hard limit
    const auto why = nod.apply(hold, 0.1, 0.1);
    REQUIRE(why);
    CHECK(nod.kind() == nodscan::NodKind::constant_rate);
    // The set-point leads the profile by 50 ms; on track, the speed is the profile's rate
    // with a 5 % margin.
    const auto out = nod.update(0.2, 0.2);
    CHECK(out.angle_rad == Approx(0.25));
    CHECK(out.speed_rad_s == Approx(1.05));
    // Lagging 0.1 rad behind where the profile is now: catch up over 0.1 s.
    CHECK(nod.update(0.2, 0.1).speed_rad_s == Approx(1.05 + 1.0));
}

TEST_CASE("Nod controller: resume restarts the profile from where the axis is")
{
    servo_daemon::NodControllerOptions o;
    o.hard_limits = {-0.1, 0.6};
    o.lead_s = 0.0;
    servo_daemon::NodController nod(o);
    nodscan::NodCommand rate;
    rate.kind = nodscan::NodKind::constant_rate;
    rate.min_tilt_rad = 0.0;
    rate.max_tilt_rad = 0.5;
    rate.rate_rad_s = 1.0;
    nod.resume(1.0, 0.3);  // nothing started yet: no effect
    CHECK_FALSE(nod.started());
    REQUIRE_FALSE(nod.apply(rate, 0.0, 0.0));
    nod.resume(10.0, 0.3);
    CHECK(nod.update(10.0, 0.3).angle_rad == Approx(0.3));
    CHECK(nod.update(10.1, 0.3).angle_rad == Approx(0.4));
    // HOLD moves at the hold speed.
    nodscan::NodCommand hold;
    hold.kind = nodscan::NodKind::hold;
    hold.hold_angle_rad = 0.2;
    REQUIRE_FALSE(nod.apply(hold, 11.0, 0.3));
    CHECK(nod.update(11.0, 0.3).angle_rad == 0.2);
    CHECK(nod.update(11.0, 0.3).speed_rad_s == o.hold_speed_rad_s);
}

TEST_CASE("Nod controller: commands that would stop the nod unseen are refused, the nod runs on")
{
    servo_daemon::NodControllerOptions o;
    o.hard_limits = {-0.2, 0.7};
    o.max_rate_rad_s = 2.0;
    o.max_nod_period_s = 120.0;
    servo_daemon::NodController nod(o);
    nodscan::NodCommand good;
    good.kind = nodscan::NodKind::constant_rate;
    good.min_tilt_rad = 0.0;
    good.max_tilt_rad = 0.5;
    good.rate_rad_s = 1.0;
    REQUIRE_FALSE(nod.apply(good, 0.0, 0.0));
    const auto refused = [&](nodscan::NodCommand c) {
        const auto why = nod.apply(c, 1.0, 0.2);
        CHECK(nod.kind() == nodscan::NodKind::constant_rate);
        CHECK(nod.update(1.0, 0.2).speed_rad_s > 0.5);  // still nodding at the good rate
        return why.value_or("(accepted)");
    };
    nodscan::NodCommand c = good;
    c.kind = static_cast<nodscan::NodKind>(99);
    CHECK(refused(c) == "unknown profile 99");
    c.kind = static_cast<nodscan::NodKind>(-1);
    CHECK(refused(c) == "unknown profile -1");
    c = good;
    c.rate_rad_s = 1e-300;
    CHECK(refused(c) == "one nod would take 1e+300 s, more than max_nod_period_s (120)");
    c.rate_rad_s = 0.5 / 100.0;  // 200 s per nod
    CHECK(refused(c) == "one nod would take 200 s, more than max_nod_period_s (120)");
    c.rate_rad_s = 2.5;
    CHECK(refused(c).find("rate 2.5 rad/s (143.239 deg/s) is above max_rate_deg_s = 114.592") == 0);
    c.rate_rad_s = std::numeric_limits<double>::quiet_NaN();
    CHECK(refused(c) == "rate must be positive");
    nodscan::NodCommand u = good;
    u.kind = nodscan::NodKind::uniform_ground_spacing;
    u.min_tilt_rad = 0.05;
    u.ground_spacing_m = 0.2;
    u.sensor_height_m = 0.87;
    u.scan_period_s = 1.0 / 37.5;
    CHECK_FALSE(servo_daemon::check_command(u, o));  // the vehicle's profile is fine
    u.ground_spacing_m = 1e-9;
    u.sensor_height_m = 1e9;
    CHECK(refused(u) == "ground spacing 1e-09 m is outside [0.001, 10] m");
    u.ground_spacing_m = 0.2;
    CHECK(refused(u) == "sensor height 1e+09 m is outside [0.01, 10] m");
    u.sensor_height_m = 10.0;
    u.ground_spacing_m = 0.001;  // 0.04 m/s of ground over ~200 m
    CHECK(refused(u).find("one nod would take ") == 0);
    // Between the refusals the controller kept the first command.
    CHECK(nod.update(0.3, 0.3).angle_rad == Approx(0.35));
}
