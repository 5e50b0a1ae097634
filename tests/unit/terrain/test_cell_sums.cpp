#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/terrain/cell_sums.hpp"
#include "ugv/terrain/point_variance.hpp"

using namespace ugv::terrain;

TEST_CASE("eq. 23 and 32: (z=1, s2=1) fused with (z=3, s2=3)")
{
    CellSums c;
    fuse_sample(c, 0.0f, 0.0f, 1.0, 1.0f / 1.0f);
    fuse_sample(c, 0.0f, 0.0f, 3.0, 1.0f / 3.0f);
    // By hand: sum 1/s2 = 1 + 1/3 = 4/3; sum z/s2 = 1 + 3/3 = 2; sum z^2/s2 = 1 + 9/3 = 4.
    // eq. 23: mean = 2 / (4/3) = 1.5.
    // eq. 32: variance = ((4/3) 4 - 2^2) / (4/3)^2 = (16/3 - 12/3) / (16/9) = (4/3)(9/16) = 0.75,
    // the same as eq. 25: ((1 - 1.5)^2 / 1 + (3 - 1.5)^2 / 3) / (4/3) = (0.25 + 0.75) / (4/3).
    const CellStatistics s = cell_statistics(c, StatisticsKind::variance_weighted);
    CHECK(s.mean_z_m == Approx(1.5).epsilon(1e-7));
    CHECK(s.variance_z_m2 == Approx(0.75).epsilon(1e-6));
    CHECK(c.w == Approx(4.0 / 3.0));
    CHECK(c.z_ref_m == 1.0f);  // the first sample's height
    CHECK(c.z_wz == Approx(2.0 / 3.0));  // (3 - 1) / 3
    CHECK(c.z_wz2 == Approx(4.0 / 3.0));  // (3 - 1)^2 / 3
}

TEST_CASE("eq. 21 and 22: classical statistics fuse with unit weight")
{
    CellSums c;
    for (double z : {1.0, 3.0, 8.0}) fuse_sample(c, 0.0f, 0.0f, z, 1.0f);
    // mean = 12 / 3 = 4; variance = ((1-4)^2 + (3-4)^2 + (8-4)^2) / (3 - 1) = (9 + 1 + 16) / 2 = 13.
    const CellStatistics s = cell_statistics(c, StatisticsKind::classical);
    CHECK(s.mean_z_m == Approx(4.0));
    CHECK(s.variance_z_m2 == Approx(13.0));
}

TEST_CASE("an empty cell is unknown; one classical sample has no variance")
{
    CellSums c;
    CHECK(std::isnan(cell_statistics(c, StatisticsKind::variance_weighted).mean_z_m));
    CHECK(std::isnan(cell_statistics(c, StatisticsKind::variance_weighted).variance_z_m2));
    fuse_sample(c, 0.0f, 0.0f, 2.0, 1.0f);
    CHECK(cell_statistics(c, StatisticsKind::classical).mean_z_m == 2.0);
    CHECK(std::isnan(cell_statistics(c, StatisticsKind::classical).variance_z_m2));
    CHECK(cell_statistics(c, StatisticsKind::variance_weighted).variance_z_m2 == 0.0);
}

TEST_CASE("eq. 32 stays non-negative for many nearly equal heights far from zero")
{
    CellSums c;
    // 10000 samples of 1234.5 m +/- 1 um with weight 1e6 (s = 1 mm): the true spread is 1e-12 m^2.
    for (int k = 0; k < 10000; ++k) fuse_sample(c, 0.0f, 0.0f, 1234.5 + ((k % 2) ? 1e-6 : -1e-6), 1.0e6f);
    const CellStatistics s = cell_statistics(c, StatisticsKind::variance_weighted);
    CHECK(s.mean_z_m == Approx(1234.5).epsilon(1e-12));
    CHECK(s.variance_z_m2 >= 0.0);
    CHECK(s.variance_z_m2 < 1e-6);
}

TEST_CASE("the x and y sums give the remainder (mean offset from the cell centre)")
{
    CellSums c;
    fuse_sample(c, 0.05f, -0.02f, 0.0, 1.0f);
    fuse_sample(c, 0.01f, -0.06f, 0.0, 3.0f);
    float x_re = 0, y_re = 0;
    mean_offset(c, x_re, y_re);
    // (0.05 * 1 + 0.01 * 3) / 4 = 0.02; (-0.02 - 0.18) / 4 = -0.05.
    CHECK(x_re == Approx(0.02f));
    CHECK(y_re == Approx(-0.05f));
}

TEST_CASE("add_sums adds every sum, z re-expressed about the first cell's reference")
{
    CellSums a, b;
    fuse_sample(a, 0.1f, 0.2f, 1.0, 2.0f);
    fuse_sample(b, -0.1f, 0.05f, 3.0, 0.5f);
    CellSums sum = a;
    add_sums(sum, b);
    CHECK(sum.z_ref_m == 1.0f);
    CHECK(sum.w == Approx(2.5));
    CHECK(sum.z_wz == Approx(0.5 * 2.0));  // b's z is 2 m above a's reference
    CHECK(sum.z_wz2 == Approx(0.5 * 4.0));
    double wz = 0.0, wz2 = 0.0;
    z_sums_about(sum, 0.0, wz, wz2);  // ENU heights: 2 * 1 + 0.5 * 3, 2 * 1 + 0.5 * 9
    CHECK(wz == Approx(2.0 + 1.5));
    CHECK(wz2 == Approx(2.0 + 4.5));
    CHECK(sum.x_wx == Approx(0.2f - 0.05f));
    CHECK(sum.x_wx2 == Approx(0.02f + 0.005f));
    CHECK(sum.y_wy == Approx(0.4f + 0.025f));
    CHECK(sum.y_wy2 == Approx(0.08f + 0.00125f));
    CellSums empty;
    add_sums(empty, b);  // into an empty cell: a copy
    CHECK(empty.z_ref_m == 3.0f);
    CHECK(empty.w == 0.5f);
}

TEST_CASE("eq. 19-20: variance = sensor part + 2 (r de)^2")
{
    // r = 10 m, de = 0.01 rad: 2 (0.1)^2 = 0.02 m^2, plus 1e-4 m^2 from the sensor.
    CHECK(point_variance_m2(1e-4f, 10.0f, 1e-4f) == Approx(0.0201f));
    CHECK(point_variance_m2(0.0f, 30.0f, 0.0f) == 0.0f);
}
