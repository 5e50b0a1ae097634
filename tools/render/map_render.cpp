#include "map_render.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace ugv::render {

namespace {

constexpr int kMargin = 10;
constexpr int kFooter = 44;
constexpr int kGap = 20;

Rgb mix(Rgb a, Rgb b, double t)
{
    auto ch = [t](uint8_t x, uint8_t y) { return static_cast<uint8_t>(std::lround(x + (y - x) * t)); };
    return {ch(a.r, b.r), ch(a.g, b.g), ch(a.b, b.b)};
}

std::string number(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

}  // namespace

Rgb elevation_colour(double t)
{
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
    const Rgb green{0, 150, 0}, yellow{235, 215, 0}, red{215, 0, 0};
    return t < 0.5 ? mix(green, yellow, t * 2.0) : mix(yellow, red, (t - 0.5) * 2.0);
}

Rgb deviation_colour(double t)
{
    t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0);
    return mix({190, 215, 255}, {0, 0, 110}, t);
}

void cell_pixel(const terrain_map_t& m, int cell_px, int i, int j, int& x, int& y)
{
    x = kMargin + (m.ny - 1 - j) * cell_px;
    y = kMargin + (m.nx - 1 - i) * cell_px;
}

namespace {

// Pixel of a point in the map frame (body-relative, map axes), in the panel at x_offset.
void map_pixel(const terrain_map_t& m, int cell_px, int x_offset, double mx, double my, int& px, int& py)
{
    const double far_x = m.origin_x + static_cast<double>(m.nx) * m.resolution;
    const double left_y = m.origin_y + static_cast<double>(m.ny) * m.resolution;
    px = x_offset + kMargin + static_cast<int>(std::lround((left_y - my) / m.resolution * cell_px));
    py = kMargin + static_cast<int>(std::lround((far_x - mx) / m.resolution * cell_px));
}

void draw_vehicle(Image& img, const terrain_map_t& m, const RenderOptions& o, int x_offset)
{
    // The map axes are the body's turned by -residual_yaw: map = R(residual_yaw) body.
    const double c = std::cos(m.residual_yaw), s = std::sin(m.residual_yaw);
    const double hw = 0.5 * o.vehicle_width_m;
    const double bx[4] = {o.vehicle_rear_x_m, o.vehicle_front_x_m, o.vehicle_front_x_m, o.vehicle_rear_x_m};
    const double by[4] = {hw, hw, -hw, -hw};
    int px[4], py[4];
    for (int k = 0; k < 4; ++k) map_pixel(m, o.cell_px, x_offset, c * bx[k] - s * by[k], s * bx[k] + c * by[k], px[k], py[k]);
    for (int k = 0; k < 4; ++k) img.line(px[k], py[k], px[(k + 1) % 4], py[(k + 1) % 4], kVehicle);
    // The reference point: row 0 of the map starts x_curr behind it.
    int rx = 0, ry = 0;
    map_pixel(m, o.cell_px, x_offset, m.origin_x + m.x_curr, 0.0, rx, ry);
    img.fill_rect(rx - 2, ry - 2, rx + 2, ry + 2, kReference);
}

}  // namespace

Image render_map(const terrain_map_t& m, const RenderOptions& o)
{
    const int panel_w = m.ny * o.cell_px, panel_h = m.nx * o.cell_px;
    const int panels = o.variance_panel ? 2 : 1;
    Image img(2 * kMargin + panels * panel_w + (panels - 1) * kGap, 2 * kMargin + panel_h + kFooter);
    const std::size_t cells = static_cast<std::size_t>(m.nx) * static_cast<std::size_t>(m.ny);
    const std::vector<float>& heights = o.layer == Layer::max ? m.max_z : o.layer == Layer::min ? m.min_z : m.mean_z;
    if (heights.size() < cells || m.variance_z.size() < cells) return img;

    double lo = o.z_min_m, hi = o.z_max_m, dev_max = 0.0;
    const double ground = m.pose.position[2];
    if (std::isfinite(o.z_span_m) && o.z_span_m > 0.0 && std::isfinite(ground)) {
        lo = ground - 0.25 * o.z_span_m;
        hi = lo + o.z_span_m;
    } else if (!std::isfinite(lo) || !std::isfinite(hi)) {
        lo = std::numeric_limits<double>::infinity();
        hi = -lo;
        for (float z : heights)
            if (std::isfinite(z)) {
                lo = std::min(lo, static_cast<double>(z));
                hi = std::max(hi, static_cast<double>(z));
            }
        if (!std::isfinite(lo)) lo = hi = 0.0;
    }
    if (hi - lo < 0.1) {
        const double mid = 0.5 * (hi + lo);
        lo = mid - 0.05;
        hi = mid + 0.05;
    }
    for (float v : m.variance_z)
        if (std::isfinite(v)) dev_max = std::max(dev_max, std::sqrt(std::max(0.0, static_cast<double>(v))));
    if (dev_max <= 0.0) dev_max = 1e-3;

    for (int i = 0; i < m.nx; ++i) {
        for (int j = 0; j < m.ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i * m.ny + j);
            int x = 0, y = 0;
            cell_pixel(m, o.cell_px, i, j, x, y);
            const float z = heights[k];
            const Rgb c = std::isfinite(z) ? elevation_colour((z - lo) / (hi - lo)) : kUnknown;
            img.fill_rect(x, y, x + o.cell_px - 1, y + o.cell_px - 1, c);
            if (o.variance_panel) {
                const float v = m.variance_z[k];
                const Rgb d = std::isfinite(z) && std::isfinite(v) ? deviation_colour(std::sqrt(std::max(0.0f, v)) / dev_max)
                                                                    : kUnknown;
                const int x2 = x + panel_w + kGap;
                img.fill_rect(x2, y, x2 + o.cell_px - 1, y + o.cell_px - 1, d);
            }
        }
    }
    for (int p = 0; p < panels; ++p) {
        const int x0 = kMargin + p * (panel_w + kGap);
        const Rgb frame{120, 120, 120};
        img.line(x0 - 1, kMargin - 1, x0 + panel_w, kMargin - 1, frame);
        img.line(x0 - 1, kMargin + panel_h, x0 + panel_w, kMargin + panel_h, frame);
        img.line(x0 - 1, kMargin - 1, x0 - 1, kMargin + panel_h, frame);
        img.line(x0 + panel_w, kMargin - 1, x0 + panel_w, kMargin + panel_h, frame);
        draw_vehicle(img, m, o, p * (panel_w + kGap));
    }

    // Footer: a 5 m scale bar with 1 m ticks, the elevation colour bar with its range, and
    // the deviation range.
    const int y0 = kMargin + panel_h + 8;
    const int metre_px = static_cast<int>(std::lround(static_cast<double>(o.cell_px) / m.resolution));
    img.fill_rect(kMargin, y0, kMargin + 5 * metre_px, y0 + 2, kVehicle);
    for (int k = 0; k <= 5; ++k) img.fill_rect(kMargin + k * metre_px, y0 - 4, kMargin + k * metre_px, y0 + 2, kVehicle);
    img.text(kMargin + 5 * metre_px + 6, y0 - 4, "5m", kVehicle, 2);
    const int bar_x = kMargin + 5 * metre_px + 40, bar_w = 100;
    for (int k = 0; k < bar_w; ++k) img.fill_rect(bar_x + k, y0 - 4, bar_x + k, y0 + 6, elevation_colour(k / (bar_w - 1.0)));
    img.text(bar_x, y0 + 12, number(lo), kVehicle, 2);
    img.text(bar_x + bar_w - 8 * 5, y0 + 12, number(hi) + "m", kVehicle, 2);
    if (o.variance_panel) {
        const int vx = kMargin + panel_w + kGap;
        for (int k = 0; k < bar_w; ++k) img.fill_rect(vx + k, y0 - 4, vx + k, y0 + 6, deviation_colour(k / (bar_w - 1.0)));
        img.text(vx, y0 + 12, "0", kVehicle, 2);
        img.text(vx + bar_w - 8 * 5, y0 + 12, number(dev_max) + "m", kVehicle, 2);
    }
    return img;
}

}  // namespace ugv::render
