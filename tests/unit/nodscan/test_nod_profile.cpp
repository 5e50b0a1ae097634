#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "ugv/nodscan/nod_profile.hpp"

using namespace ugv::nodscan;
using Catch::Detail::Approx;

namespace {
const TiltLimits kHard{-0.2, 0.9};

NodCommand uniform(double h, double spacing, double period, double min_tilt, double max_tilt)
{
    NodCommand c;
    c.kind = NodKind::uniform_ground_spacing;
    c.sensor_height_m = h;
    c.ground_spacing_m = spacing;
    c.scan_period_s = period;
    c.min_tilt_rad = min_tilt;
    c.max_tilt_rad = max_tilt;
    return c;
}

NodCommand constant_rate(double min_tilt, double max_tilt, double rate)
{
    NodCommand c;
    c.kind = NodKind::constant_rate;
    c.min_tilt_rad = min_tilt;
    c.max_tilt_rad = max_tilt;
    c.rate_rad_s = rate;
    return c;
}
}  // namespace

TEST_CASE("Commands outside the tilt limits, or malformed, are refused with a reason")
{
    NodCommand hold;
    hold.kind = NodKind::hold;
    hold.hold_angle_rad = 0.5;
    CHECK_FALSE(validate(hold, kHard));
    hold.hold_angle_rad = 1.0;
    REQUIRE(validate(hold, kHard));
    CHECK(validate(hold, kHard)->find("outside the tilt limits") != std::string::npos);
    hold.hold_angle_rad = NAN;
    CHECK(validate(hold, kHard));

    CHECK_FALSE(validate(constant_rate(0.0, 0.5, 1.0), kHard));
    CHECK(validate(constant_rate(-0.3, 0.5, 1.0), kHard));  // below the lower limit
    CHECK(validate(constant_rate(0.0, 0.95, 1.0), kHard));  // above the upper limit
    CHECK(validate(constant_rate(0.5, 0.5, 1.0), kHard));   // empty range
    CHECK(validate(constant_rate(0.0, 0.5, 0.0), kHard));   // no rate
    CHECK(validate(constant_rate(0.0, 0.5, -1.0), kHard));

    CHECK_FALSE(validate(uniform(1.0, 0.2, 0.0267, 0.1, 0.6), kHard));
    CHECK(validate(uniform(1.0, 0.2, 0.0267, 0.0, 0.6), kHard));  // horizon never reaches the ground
    CHECK(validate(uniform(0.0, 0.2, 0.0267, 0.1, 0.6), kHard));
    CHECK(validate(uniform(1.0, 0.0, 0.0267, 0.1, 0.6), kHard));
    CHECK(validate(uniform(1.0, 0.2, 0.0, 0.1, 0.6), kHard));
    NodCommand stop;
    CHECK_FALSE(validate(stop, kHard));
}

TEST_CASE("Constant rate is a triangle between the limits")
{
    NodProfile p;
    p.start(constant_rate(0.0, 0.5, 0.5), 10.0, 0.0);
    CHECK(p.nod_period_s() == Approx(2.0));
    CHECK(p.at(10.0).angle_rad == Approx(0.0));
    CHECK(p.at(10.5).angle_rad == Approx(0.25));
    CHECK(p.at(10.5).velocity_rad_s == Approx(0.5));
    CHECK(p.at(11.0).angle_rad == Approx(0.5));
    CHECK(p.at(11.5).angle_rad == Approx(0.25));
    CHECK(p.at(11.5).velocity_rad_s == Approx(-0.5));
    CHECK(p.at(12.0).angle_rad == Approx(0.0).margin(1e-12));
    CHECK(p.at(13.25).angle_rad == Approx(0.375));  // 1.5 periods + 0.25 s: on the way down
}

TEST_CASE("A nod starts from the current angle, heading towards max tilt")
{
    NodProfile p;
    p.start(constant_rate(0.0, 0.5, 0.5), 0.0, 0.3);
    CHECK(p.at(0.0).angle_rad == Approx(0.3));
    CHECK(p.at(0.2).angle_rad == Approx(0.4));
    p.start(constant_rate(0.0, 0.5, 0.5), 0.0, 0.8);  // outside the range: starts at its edge
    CHECK(p.at(0.0).angle_rad == Approx(0.5));
    CHECK(p.at(0.2).angle_rad == Approx(0.4));
}

TEST_CASE("Every profile stays inside its limits")
{
    NodProfile p;
    for (const auto& c : {constant_rate(-0.1, 0.7, 1.3), uniform(0.9, 0.2, 1.0 / 37.5, 0.08, 0.7)}) {
        p.start(c, 0.0, 0.2);
        for (double t = 0.0; t < 30.0; t += 0.0007) {
            const double a = p.at(t).angle_rad;
            REQUIRE(a >= c.min_tilt_rad);
            REQUIRE(a <= c.max_tilt_rad);
        }
    }
}

TEST_CASE("STOP holds the angle where it started, HOLD its own angle")
{
    NodProfile p;
    NodCommand c;
    p.start(c, 0.0, 0.123);
    CHECK(p.at(5.0).angle_rad == 0.123);
    CHECK(p.at(5.0).velocity_rad_s == 0.0);
    c.kind = NodKind::hold;
    c.hold_angle_rad = -0.05;
    p.start(c, 0.0, 0.123);
    CHECK(p.at(5.0).angle_rad == -0.05);
}

TEST_CASE("Uniform ground spacing: successive scans hit a flat floor evenly spaced (within 10%)")
{
    // A laser 0.87 m up scanning at 37.5 Hz, spacing matched to a 0.2 m grid, ground from
    // 1.5 m to 12 m.
    const double h = 0.87, spacing = 0.2, period = 1.0 / 37.5;
    const auto c = uniform(h, spacing, period, std::atan2(h, 12.0), std::atan2(h, 1.5));
    NodProfile p;
    p.start(c, 0.0, c.min_tilt_rad);
    std::vector<double> hits;
    for (int k = 0; k < 400; ++k) hits.push_back(ground_distance(h, p.at(k * period).angle_rad));
    int checked = 0;
    for (std::size_t k = 2; k < hits.size(); ++k) {
        const double step = hits[k] - hits[k - 1];
        const double previous = hits[k - 1] - hits[k - 2];
        if (step * previous <= 0.0) continue;  // the pair straddles a turn-around at a range end
        CHECK(std::fabs(step) == Approx(spacing).epsilon(0.10));
        ++checked;
    }
    CHECK(checked > 350);
    // It does nod over the whole range: near and far ends are both reached.
    CHECK(*std::min_element(hits.begin(), hits.end()) < 1.5 + spacing);
    CHECK(*std::max_element(hits.begin(), hits.end()) > 12.0 - spacing);
    // For comparison, a constant rate over the same range does not space them evenly.
    NodProfile rate;
    rate.start(constant_rate(c.min_tilt_rad, c.max_tilt_rad, 0.3), 0.0, c.min_tilt_rad);
    const double near = ground_distance(h, rate.at(2.0 * period).angle_rad) - ground_distance(h, rate.at(3.0 * period).angle_rad);
    CHECK(std::fabs(near) > 1.5 * spacing);
}

TEST_CASE("Uniform ground spacing: the rate matches dtheta = Dd h / (h^2 + d^2) per scan")
{
    const double h = 1.0, spacing = 0.2, period = 0.025;
    const auto c = uniform(h, spacing, period, std::atan2(h, 10.0), std::atan2(h, 2.0));
    NodProfile p;
    p.start(c, 0.0, std::atan2(h, 5.0));
    const auto s = p.at(0.0);
    const double d = 5.0;
    CHECK(s.angle_rad == Approx(std::atan2(h, d)));
    CHECK(s.velocity_rad_s * period == Approx(spacing * h / (h * h + d * d)));
    // Over one scan period the hit moves from d to d - spacing; the formula taken at the
    // midpoint of that step gives the angle change.
    const double mid = d - spacing / 2;
    CHECK(p.at(period).angle_rad - p.at(0.0).angle_rad == Approx(spacing * h / (h * h + mid * mid)).epsilon(0.002));
}
