#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/simworld/height_field.hpp"

using namespace ugv::simworld;

TEST_CASE("a beam pitched down onto a flat floor hits at height / sin(pitch)")
{
    HeightField f(-10, -10, 0.05, 400, 400, 0.0f);
    for (double pitch_deg : {2.0, 10.0, 45.0, 89.0}) {
        const double p = pitch_deg * M_PI / 180.0;
        const Eigen::Vector3d dir(std::cos(p) * std::cos(0.3), std::cos(p) * std::sin(0.3), -std::sin(p));
        const double r = ray_cast(f, {0.01, 0.02, 0.87}, dir, 80.0);
        if (pitch_deg == 2.0) CHECK(std::isinf(r));  // 24.9 m: leaves the 10 m field first
        else CHECK(r == Approx(0.87 / std::sin(p)).epsilon(1e-9));
    }
    // Straight down and level.
    CHECK(ray_cast(f, {1, 1, 2}, {0, 0, -1}, 80) == Approx(2.0));
    CHECK(std::isinf(ray_cast(f, {1, 1, 2}, {1, 0, 0}, 80)));
    CHECK(std::isinf(ray_cast(f, {0, 0, 0.87}, Eigen::Vector3d(1, 0, -0.1).normalized(), 5.0)));  // beyond max range
}

TEST_CASE("a box is hit on its side and on its top")
{
    HeightField f(0, -5, 0.1, 200, 100, 0.0f);
    for (int i = 50; i < 60; ++i)  // x in [5, 6)
        for (int j = 40; j < 60; ++j) f.at(i, j) = 1.0f;
    // Level beam at 0.5 m: hits the face x = 5.
    CHECK(ray_cast(f, {1, 0, 0.5}, {1, 0, 0}, 80) == Approx(4.0));
    // From above, steep: lands on the top at z = 1.
    const Eigen::Vector3d d = Eigen::Vector3d(1, 0, -1).normalized();
    CHECK(ray_cast(f, {4.5, 0, 2.0}, d, 80) == Approx(std::sqrt(2.0)));  // (5.5, 0, 1)
    // Backwards (negative x direction) onto the far face x = 6.
    CHECK(ray_cast(f, {9, 0, 0.5}, {-1, 0, 0}, 80) == Approx(3.0));
}

TEST_CASE("height lookups and the truth file round trip")
{
    HeightField f(-1.0, 2.0, 0.25, 3, 4, 0.5f);
    f.at(2, 3) = -0.75f;
    CHECK(f.height_at(-1.0 + 2.6 * 0.25, 2.0 + 3.1 * 0.25) == -0.75);
    CHECK(f.height_at(-0.5, 2.1) == 0.5);
    CHECK(std::isnan(f.height_at(-1.01, 2.1)));
    CHECK(std::isnan(f.height_at(-0.5, 3.0)));
    CHECK(std::isnan(f.height_at(-0.2, 2.1)));
    const HeightField g = decode_height_field(encode_height_field(f));
    CHECK(g.nx == 3);
    CHECK(g.ny == 4);
    CHECK(g.resolution_m == 0.25);
    CHECK(g.origin_x_m == -1.0);
    CHECK(g.origin_y_m == 2.0);
    CHECK(g.z_m == f.z_m);
    std::string bytes = encode_height_field(f);
    CHECK_THROWS_WITH(decode_height_field(bytes.substr(0, bytes.size() - 1)),
                      "height field holds 47 bytes of heights, 48 expected");
    CHECK_THROWS_WITH(decode_height_field("P5 3 4\n"), "not a height field (no UGVHF1 header)");
    CHECK_THROWS_WITH(decode_height_field("UGVHF1 3 -4 0.25 0 0\n"), "bad height field header");
}
