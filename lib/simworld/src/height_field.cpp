#include "ugv/simworld/height_field.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace ugv::simworld {

HeightField::HeightField(double origin_x, double origin_y, double resolution, int cells_x, int cells_y, float z)
    : origin_x_m(origin_x),
      origin_y_m(origin_y),
      resolution_m(resolution),
      nx(cells_x),
      ny(cells_y),
      z_m(static_cast<std::size_t>(cells_x) * static_cast<std::size_t>(cells_y), z)
{
}

double HeightField::height_at(double x_m, double y_m) const
{
    const double fi = std::floor((x_m - origin_x_m) / resolution_m);
    const double fj = std::floor((y_m - origin_y_m) / resolution_m);
    if (!(fi >= 0 && fi < nx && fj >= 0 && fj < ny)) return std::numeric_limits<double>::quiet_NaN();
    return at(static_cast<int>(fi), static_cast<int>(fj));
}

double ray_cast(const HeightField& f, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double max_range_m)
{
    constexpr double inf = std::numeric_limits<double>::infinity();
    const double res = f.resolution_m;
    double gx = (o.x() - f.origin_x_m) / res;  // in cell units
    double gy = (o.y() - f.origin_y_m) / res;
    int i = static_cast<int>(std::floor(gx));
    int j = static_cast<int>(std::floor(gy));
    // Amanatides-Woo traversal of the columns the ray's ground track crosses; in each, the ray
    // is below the top either on entry (it hit the column's side) or by the exit (its top).
    const int step_i = d.x() > 0 ? 1 : -1;
    const int step_j = d.y() > 0 ? 1 : -1;
    const double dx = std::abs(d.x()), dy = std::abs(d.y());
    const double t_delta_x = dx > 0 ? res / dx : inf;
    const double t_delta_y = dy > 0 ? res / dy : inf;
    double t_max_x = dx > 0 ? ((step_i > 0 ? (i + 1 - gx) : (gx - i)) * res) / dx : inf;
    double t_max_y = dy > 0 ? ((step_j > 0 ? (j + 1 - gy) : (gy - j)) * res) / dy : inf;
    double t_in = 0.0;
    while (t_in <= max_range_m) {
        if (i < 0 || i >= f.nx || j < 0 || j >= f.ny) return inf;
        const double top = f.at(i, j);
        const double t_out = std::min({t_max_x, t_max_y, max_range_m});
        const double z_in = o.z() + d.z() * t_in;
        if (z_in <= top) return t_in;                      // the side of the column
        const double z_out = o.z() + d.z() * t_out;
        if (z_out <= top) return (top - o.z()) / d.z();    // its top (d.z() < 0 here)
        if (t_out >= max_range_m) return inf;
        t_in = t_out;
        if (t_max_x < t_max_y) {
            i += step_i;
            t_max_x += t_delta_x;
        } else {
            j += step_j;
            t_max_y += t_delta_y;
        }
    }
    return inf;
}

std::string encode_height_field(const HeightField& f)
{
    std::ostringstream header;
    header.precision(17);
    header << "UGVHF1 " << f.nx << ' ' << f.ny << ' ' << f.resolution_m << ' ' << f.origin_x_m << ' ' << f.origin_y_m
           << '\n';
    std::string out = header.str();
    const std::size_t at = out.size();
    out.resize(at + f.z_m.size() * sizeof(float));
    std::memcpy(out.data() + at, f.z_m.data(), f.z_m.size() * sizeof(float));  // little-endian hosts only
    return out;
}

HeightField decode_height_field(const std::string& bytes)
{
    const std::size_t eol = bytes.find('\n');
    if (bytes.compare(0, 7, "UGVHF1 ") != 0 || eol == std::string::npos)
        throw std::invalid_argument("not a height field (no UGVHF1 header)");
    std::istringstream header(bytes.substr(7, eol - 7));
    HeightField f;
    header >> f.nx >> f.ny >> f.resolution_m >> f.origin_x_m >> f.origin_y_m;
    if (!header || f.nx <= 0 || f.ny <= 0 || f.nx > 100000 || f.ny > 100000 || !(f.resolution_m > 0))
        throw std::invalid_argument("bad height field header");
    const std::size_t n = static_cast<std::size_t>(f.nx) * static_cast<std::size_t>(f.ny);
    if (bytes.size() - eol - 1 != n * sizeof(float))
        throw std::invalid_argument("height field holds " + std::to_string(bytes.size() - eol - 1) + " bytes of heights, " +
                                    std::to_string(n * sizeof(float)) + " expected");
    f.z_m.resize(n);
    std::memcpy(f.z_m.data(), bytes.data() + eol + 1, n * sizeof(float));
    return f;
}

}  // namespace ugv::simworld
