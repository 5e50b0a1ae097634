#include <catch2/catch.hpp>

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
