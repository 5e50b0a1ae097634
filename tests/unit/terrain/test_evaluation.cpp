#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/terrain/evaluation.hpp"

using namespace ugv::terrain;

TEST_CASE("evaluate: bias, RMSE, coverage and obstacles against a height field")
{
    MapSnapshot m;
    m.nx = 2;
    m.ny = 2;
    m.resolution_m = 1.0;
    m.origin_x_m = 0.0;
    m.origin_y_m = -1.0;
    m.pose.position_m = {10.0, 20.0, 0.0};
    m.pose.orientation = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ());  // facing north
    // Cell (i, j) centre in the map frame: (i + 0.5, j - 0.5); facing north, world = (10 - y, 20 + x).
    CHECK(cell_centre_world(m, 1, 0).x() == Approx(10.5));
    CHECK(cell_centre_world(m, 1, 0).y() == Approx(21.5));
    m.mean_z_m = {0.05f, NAN, 1.0f, -0.1f};     // (0,0) (0,1) (1,0) (1,1)
    m.variance_z_m2 = {0.01f, NAN, 0.03f, 0.02f};
    // Truth: ground at 0 except an obstacle of 1.2 m around (10.5, 21.5), i.e. cell (1, 0).
    auto truth = [](double x, double y) { return (std::abs(x - 10.5) < 0.4 && std::abs(y - 21.5) < 0.4) ? 1.2 : 0.0; };
    const MapMetrics r = evaluate(m, truth, 0.2);
    CHECK(r.cells == 4);
    CHECK(r.known == 3);
    CHECK(r.coverage == Approx(0.75));
    // Errors 0.05, -0.2, -0.1: bias -0.25/3, RMSE sqrt((0.0025 + 0.04 + 0.01) / 3).
    CHECK(r.bias_m == Approx(-0.25 / 3).epsilon(1e-6));
    CHECK(r.rmse_m == Approx(std::sqrt(0.0525 / 3)).epsilon(1e-6));
    CHECK(r.mean_cell_variance_m2 == Approx(0.02).epsilon(1e-6));
    CHECK(r.obstacle_cells == 1);
    CHECK(r.obstacles_detected == 1);
    CHECK(r.false_obstacles == 0);
    CHECK(r.max_bias_m == 0.0);  // no max_z_m in this map
    CHECK(r.obstacle_mean_error_m == Approx(-0.2).epsilon(1e-6));
}

TEST_CASE("evaluate: the highest sample of a wall's cell says how tall the wall is")
{
    MapSnapshot m;
    m.nx = 1;
    m.ny = 2;
    m.resolution_m = 1.0;
    m.origin_x_m = 0.0;
    m.origin_y_m = -1.0;
    m.pose.orientation = Eigen::Quaterniond::Identity();
    // Cell (0, 0): ground; cell (0, 1): a 1.5 m wall whose samples span 0 to 1.5 m.
    m.mean_z_m = {0.01f, 0.6f};
    m.variance_z_m2 = {0.0f, 0.3f};
    m.max_z_m = {0.03f, 1.5f};
    m.min_z_m = {-0.01f, 0.0f};
    auto truth = [](double, double y) { return y > 0.0 ? 1.5 : 0.0; };
    const MapMetrics r = evaluate(m, truth, 0.2);
    CHECK(r.obstacle_cells == 1);
    CHECK(r.obstacle_mean_error_m == Approx(-0.9).epsilon(1e-6));
    CHECK(r.obstacle_max_error_m == Approx(0.0).margin(1e-6));
    CHECK(r.max_bias_m == Approx(0.015).epsilon(1e-5));  // (0.03 + 0) / 2
    CHECK(r.max_rmse_m == Approx(std::sqrt(0.0009 / 2)).epsilon(1e-5));
}

TEST_CASE("area_coverage: the known share of the cells ahead, placed with the map's yaw residual")
{
    MapSnapshot m;
    m.nx = 3;
    m.ny = 2;
    m.resolution_m = 1.0;
    m.origin_x_m = 0.0;
    m.origin_y_m = -1.0;
    // Centres: x 0.5, 1.5, 2.5 ahead; y -0.5, 0.5. Known: (1, 0), (2, 1) and (0, 0).
    m.mean_z_m = {0.0f, NAN, 0.1f, NAN, NAN, 0.2f};
    AreaCoverage a = area_coverage(m, {1.0, 3.0, 1.0});
    CHECK(a.cells == 4);
    CHECK(a.known == 2);
    CHECK(a.coverage == Approx(0.5));
    a = area_coverage(m, {1.0, 3.0, 0.4});  // no centre within 0.4 m of the centre line
    CHECK(a.cells == 0);
    CHECK(a.coverage == 0.0);
    // The map's axes 90 deg to the right of the body's: a map cell at x = 2.5 lies 2.5 m to
    // the vehicle's right, outside an area straight ahead.
    m.residual_yaw_rad = M_PI / 2;
    a = area_coverage(m, {-1.0, 1.0, 3.0});
    CHECK(a.cells == 6);
    CHECK(a.known == 3);
    a = area_coverage(m, {1.0, 3.0, 3.0});
    CHECK(a.cells == 0);
    m.mean_z_m.clear();  // a map without cells
    CHECK(area_coverage(m, {-1.0, 1.0, 3.0}).cells == 0);
}
