#include "traverse_render.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

namespace ugv::render {

namespace {

constexpr int kLegendGap = 16;   // between the map and the legend
constexpr int kRow = 18;         // legend row height
constexpr int kSwatchW = 24;
constexpr int kMaxCells = 2000;  // per side: a bigger map is not one this tool can draw
constexpr int kMaxPanelPx = 8000;  // per side: --cell-px is lowered to keep the picture below
constexpr int kMaxArcs = 1000;
constexpr int kMaxArcSamples = 100000;
constexpr int kDashOnPx = 6, kDashPeriodPx = 10;

Rgb mix(Rgb a, Rgb b, double t)
{
    auto ch = [t](uint8_t x, uint8_t y) { return static_cast<uint8_t>(std::lround(x + (y - x) * t)); };
    return {ch(a.r, b.r), ch(a.g, b.g), ch(a.b, b.b)};
}

std::string format(const char* fmt, double v)
{
    char buf[48];
    std::snprintf(buf, sizeof buf, fmt, v);
    return buf;
}

std::string format_int(const char* fmt, long long a, long long b = 0)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, fmt, a, b);
    return buf;
}

// The map panel's pixel rectangle, inclusive.
struct Panel
{
    int x0, y0, x1, y1;
    bool inside(int x, int y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

Panel panel_of(const traversability_map_t& m, int cell_px)
{
    return {kTraverseMargin, kTraverseMargin, kTraverseMargin + m.ny * cell_px - 1, kTraverseMargin + m.nx * cell_px - 1};
}

// A w x w dot centred on (x, y), clipped to the panel.
void dot(Image& img, const Panel& p, int x, int y, int w, Rgb c)
{
    const int x0 = x - (w - 1) / 2, y0 = y - (w - 1) / 2;
    for (int yy = y0; yy < y0 + w; ++yy)
        for (int xx = x0; xx < x0 + w; ++xx)
            if (p.inside(xx, yy)) img.set(xx, yy, c);
}

void cross(Image& img, const Panel& p, int x, int y, Rgb c)
{
    for (int d = -4; d <= 4; ++d) {
        dot(img, p, x + d, y + d, 2, c);
        dot(img, p, x + d, y - d, 2, c);
    }
}

void map_point_pixel(const traversability_map_t& m, int cell_px, double mx, double my, int& x, int& y)
{
    const double far_x = m.origin_x + static_cast<double>(m.nx) * m.resolution;
    const double left_y = m.origin_y + static_cast<double>(m.ny) * m.resolution;
    const double px = (left_y - my) / m.resolution * cell_px, py = (far_x - mx) / m.resolution * cell_px;
    // Clamped before the conversion: a point far off the map (or not a number, from an
    // outline option) is off the panel all the same.
    auto to_px = [](double v) { return static_cast<int>(std::floor(std::isfinite(v) ? std::clamp(v, -1e6, 1e6) : -1e6)); };
    x = kTraverseMargin + to_px(px);
    y = kTraverseMargin + to_px(py);
}

// Body frame -> map axes: map = R(residual_yaw) body (the map's axes are the body's turned
// by -residual_yaw).
void body_pixel(const traversability_map_t& m, int cell_px, double bx, double by, int& x, int& y)
{
    const double c = std::cos(m.residual_yaw), s = std::sin(m.residual_yaw);
    map_point_pixel(m, cell_px, c * bx - s * by, s * bx + c * by, x, y);
}

// Samples for a line of n pixels, clamped in double before the conversion.
int samples(double n)
{
    return static_cast<int>(std::clamp(std::ceil(n), 1.0, static_cast<double>(kMaxArcSamples)));
}

// The body-frame point s_m along an arc from the origin heading +X; the series below 1e-6 rad
// of turn avoids 0/0.
void arc_point(double curvature, double s_m, double& bx, double& by)
{
    const double ks = curvature * s_m;
    bx = std::abs(ks) < 1e-6 ? s_m : std::sin(ks) / curvature;
    by = std::abs(ks) < 1e-6 ? 0.5 * curvature * s_m * s_m : (1.0 - std::cos(ks)) / curvature;
}

void draw_arc(Image& img, const Panel& p, const traversability_map_t& m, int cell_px, double curvature, double s_end,
              int width, bool dashed, Rgb c)
{
    const double px_per_m = cell_px / static_cast<double>(m.resolution);
    const int steps = samples(s_end * px_per_m * 2.0);
    for (int k = 0; k <= steps; ++k) {
        const double s = s_end * k / steps;
        if (dashed && std::fmod(s * px_per_m, kDashPeriodPx) >= kDashOnPx) continue;
        int x = 0, y = 0;
        arc_pixel(m, cell_px, curvature, s, x, y);
        dot(img, p, x, y, width, c);
    }
}

// Where a blocked arc's vehicle stops, the body origin clear_m along the arc: on from
// there along its heading to the front bumper (where the footprint meets the obstacle),
// dashed, and a cross at the bumper.
void draw_hit(Image& img, const Panel& p, const traversability_map_t& m, const TraverseOptions& o, double curvature,
              double clear_m)
{
    const double ks = curvature * clear_m;
    double bx = 0, by = 0;
    arc_point(curvature, clear_m, bx, by);
    const double px_per_m = o.cell_px / static_cast<double>(m.resolution);
    const double front = std::max(0.0, o.vehicle_front_x_m);
    const int steps = samples(front * px_per_m * 2.0);
    int x = 0, y = 0;
    for (int k = 0; k <= steps; ++k) {
        const double d = front * k / steps;
        if (std::fmod((clear_m + d) * px_per_m, kDashPeriodPx) >= kDashOnPx) continue;
        body_pixel(m, o.cell_px, bx + d * std::cos(ks), by + d * std::sin(ks), x, y);
        dot(img, p, x, y, 2, kBlockedArc);
    }
    body_pixel(m, o.cell_px, bx + front * std::cos(ks), by + front * std::sin(ks), x, y);
    cross(img, p, x, y, kBlockedArc);
}

void draw_vehicle(Image& img, const Panel& p, const traversability_map_t& m, const TraverseOptions& o)
{
    const double hw = 0.5 * o.vehicle_width_m;
    const double bx[4] = {o.vehicle_rear_x_m, o.vehicle_front_x_m, o.vehicle_front_x_m, o.vehicle_rear_x_m};
    const double by[4] = {hw, hw, -hw, -hw};
    int px[4], py[4];
    for (int k = 0; k < 4; ++k) body_pixel(m, o.cell_px, bx[k], by[k], px[k], py[k]);
    // Drawn dot by dot so that it stays on the panel.
    for (int k = 0; k < 4; ++k) {
        const int n = std::max(std::abs(px[(k + 1) % 4] - px[k]), std::abs(py[(k + 1) % 4] - py[k]));
        for (int t = 0; t <= std::min(n, 100000); ++t) {
            const double f = n > 0 ? static_cast<double>(t) / n : 0.0;
            dot(img, p, static_cast<int>(std::lround(px[k] + f * (px[(k + 1) % 4] - px[k]))),
                static_cast<int>(std::lround(py[k] + f * (py[(k + 1) % 4] - py[k]))), 1, kOutline);
        }
    }
    int x = 0, y = 0;
    body_pixel(m, o.cell_px, 0.0, 0.0, x, y);
    dot(img, p, x, y, 4, kOutline);  // the body origin, where the arcs start
}

void draw_legend(Image& img, const traversability_map_t& m, const candidate_arcs_t* arcs, int cell_px, int x0, int y0)
{
    const Rgb ink = kOutline;
    int y = y0;
    auto label = [&](const std::string& s) { img.text(x0 + kSwatchW + 8, y + 1, s, ink, 2); };
    auto swatch = [&](Rgb c, const std::string& s) {
        img.fill_rect(x0, y, x0 + kSwatchW - 1, y + 11, c);
        label(s);
        y += kRow;
    };
    swatch(kTraversableEasy, "TRAVERSABLE");
    for (int k = 0; k < kSwatchW; ++k) img.fill_rect(x0 + k, y, x0 + k, y + 11, traversable_colour(k / (kSwatchW - 1.0)));
    label("COST 0 TO 1");
    y += kRow;
    swatch(kObstacle, "OBSTACLE");
    swatch(kNegativeObstacle, "NEG. OBSTACLE");
    swatch(kUnknownCell, "UNKNOWN");
    img.fill_rect(x0, y + 5, x0 + kSwatchW - 1, y + 6, kFreeArc);
    label("FREE ARC");
    y += kRow;
    for (int k = 0; k < kSwatchW; ++k)
        if (k % kDashPeriodPx < kDashOnPx) img.fill_rect(x0 + k, y + 5, x0 + k, y + 6, kBlockedArc);
    label("BLOCKED ARC");
    y += kRow;
    for (int d = -4; d <= 4; ++d) {
        img.fill_rect(x0 + 12 + d, y + 6 + d, x0 + 13 + d, y + 7 + d, kBlockedArc);
        img.fill_rect(x0 + 12 + d, y + 6 - d, x0 + 13 + d, y + 7 - d, kBlockedArc);
    }
    label("HIT");
    y += kRow;
    img.fill_rect(x0, y + 4, x0 + kSwatchW - 1, y + 7, kBestArc);
    label("BEST ARC");
    y += kRow;
    img.line(x0, y, x0 + kSwatchW - 1, y, kOutline);
    img.line(x0, y + 11, x0 + kSwatchW - 1, y + 11, kOutline);
    img.line(x0, y, x0, y + 11, kOutline);
    img.line(x0 + kSwatchW - 1, y, x0 + kSwatchW - 1, y + 11, kOutline);
    label("VEHICLE");
    y += kRow + kRow / 2;

    // A scale bar of the longest of 10, 5, 2, 1 m that fits, with 1 m ticks.
    const double metre_px = cell_px / static_cast<double>(m.resolution);
    int metres = 1;
    for (int cand : {10, 5, 2})
        if (cand * metre_px <= kLegendWidth - kLegendGap - 34) {  // room for "10m"
            metres = cand;
            break;
        }
    const int bar_px = static_cast<int>(std::lround(metres * metre_px));
    img.fill_rect(x0, y + 8, x0 + bar_px, y + 10, ink);
    for (int k = 0; k <= metres; ++k) {
        const int tx = x0 + static_cast<int>(std::lround(k * metre_px));
        img.fill_rect(tx, y + 4, tx, y + 10, ink);
    }
    img.text(x0 + bar_px + 6, y + 3, std::to_string(metres) + "m", ink, 2);
    y += kRow + kRow / 2;

    img.text(x0, y, format_int("MAP SEQ %lld", static_cast<long long>(m.map_seq)), ink, 2);
    y += kRow;
    if (!arcs) {
        img.text(x0, y, "NO ARCS FOR THIS MAP", ink, 2);
        return;
    }
    int blocked = 0;
    for (int8_t b : arcs->blocked) blocked += b != 0;
    if (arcs->best >= 0)
        img.text(x0, y, format_int("BEST: ARC %lld", arcs->best), ink, 2);
    else
        img.text(x0, y, "ALL ARCS BLOCKED", ink, 2);
    y += kRow;
    img.text(x0, y, format_int("BLOCKED %lld OF %lld", blocked, arcs->narcs), ink, 2);
    y += kRow;
    img.text(x0, y, "LENGTH " + format("%.1f", arcs->length_m) + "m", ink, 2);
    y += kRow;
    img.text(x0, y, "SWEPT " + format("%.2f", arcs->swept_width_m) + "m", ink, 2);
}

}  // namespace

Rgb traversable_colour(double cost)
{
    return mix(kTraversableEasy, kTraversableHard, std::clamp(std::isfinite(cost) ? cost : 0.0, 0.0, 1.0));
}

Rgb class_colour(int8_t cell_class, float cost)
{
    switch (cell_class) {
        case traversability_map_t::CLASS_TRAVERSABLE: return traversable_colour(cost);
        case traversability_map_t::CLASS_OBSTACLE: return kObstacle;
        case traversability_map_t::CLASS_NEGATIVE_OBSTACLE: return kNegativeObstacle;
        default: return kUnknownCell;  // CLASS_UNKNOWN, and a class this tool does not know
    }
}

bool drawable(const traversability_map_t& m)
{
    const auto n = static_cast<std::size_t>(m.ncells);
    return m.nx > 0 && m.ny > 0 && m.nx <= kMaxCells && m.ny <= kMaxCells &&
           static_cast<int64_t>(m.nx) * m.ny == m.ncells && m.cell_class.size() == n && m.cost.size() == n &&
           std::isfinite(m.resolution) && m.resolution >= 1e-3f && std::isfinite(m.origin_x) &&
           std::isfinite(m.origin_y) && std::isfinite(m.residual_yaw);
}

bool drawable(const candidate_arcs_t& a)
{
    const auto n = static_cast<std::size_t>(a.narcs);
    return a.narcs >= 0 && a.narcs <= kMaxArcs && a.curvature.size() == n && a.clear_distance_m.size() == n &&
           a.blocked.size() == n && std::isfinite(a.length_m) && a.length_m > 0.0f && a.best >= -1 &&
           a.best < a.narcs;
}

bool same_terrain_map(const traversability_map_t& m, const candidate_arcs_t& a)
{
    return m.map_seq == a.map_seq && m.utime == a.utime;
}

void traverse_cell_pixel(const traversability_map_t& m, int cell_px, int i, int j, int& x, int& y)
{
    x = kTraverseMargin + (m.ny - 1 - j) * cell_px;
    y = kTraverseMargin + (m.nx - 1 - i) * cell_px;
}

void arc_pixel(const traversability_map_t& m, int cell_px, double curvature, double s_m, int& x, int& y)
{
    double bx = 0, by = 0;
    arc_point(curvature, s_m, bx, by);
    body_pixel(m, cell_px, bx, by, x, y);
}

Image render_traverse(const traversability_map_t& m, const candidate_arcs_t* arcs, const TraverseOptions& options)
{
    if (!drawable(m)) return Image(2 * kTraverseMargin + kLegendWidth, 2 * kTraverseMargin + kLegendHeight);
    TraverseOptions o = options;
    o.cell_px = std::clamp(o.cell_px, 1, std::max(1, kMaxPanelPx / std::max(m.nx, m.ny)));
    if (arcs && (!drawable(*arcs) || !same_terrain_map(m, *arcs))) arcs = nullptr;
    const int panel_w = m.ny * o.cell_px, panel_h = m.nx * o.cell_px;
    Image img(2 * kTraverseMargin + panel_w + kLegendWidth, 2 * kTraverseMargin + std::max(panel_h, kLegendHeight));
    const Panel p = panel_of(m, o.cell_px);

    for (int i = 0; i < m.nx; ++i)
        for (int j = 0; j < m.ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * static_cast<std::size_t>(m.ny) + static_cast<std::size_t>(j);
            int x = 0, y = 0;
            traverse_cell_pixel(m, o.cell_px, i, j, x, y);
            img.fill_rect(x, y, x + o.cell_px - 1, y + o.cell_px - 1, class_colour(m.cell_class[k], m.cost[k]));
        }
    const Rgb frame{120, 120, 120};
    img.line(p.x0 - 1, p.y0 - 1, p.x1 + 1, p.y0 - 1, frame);
    img.line(p.x0 - 1, p.y1 + 1, p.x1 + 1, p.y1 + 1, frame);
    img.line(p.x0 - 1, p.y0 - 1, p.x0 - 1, p.y1 + 1, frame);
    img.line(p.x1 + 1, p.y0 - 1, p.x1 + 1, p.y1 + 1, frame);

    if (arcs) {
        // Free arcs, then blocked ones over them, then the best over everything.
        const double length = arcs->length_m;
        for (int pass = 0; pass < 2; ++pass)
            for (int a = 0; a < arcs->narcs; ++a) {
                const auto k = static_cast<std::size_t>(a);
                const bool blocked = arcs->blocked[k] != 0;
                if (blocked != (pass == 1) || a == arcs->best || !std::isfinite(arcs->curvature[k])) continue;
                const float clear = arcs->clear_distance_m[k];
                const double end = std::isfinite(clear) ? std::clamp(static_cast<double>(clear), 0.0, length) : length;
                draw_arc(img, p, m, o.cell_px, arcs->curvature[k], end, 2, blocked, blocked ? kBlockedArc : kFreeArc);
                // A blocked arc without a hit within its length was blocked by unknown cells
                // (the cautious policy): no cross.
                if (blocked && end < length) draw_hit(img, p, m, o, arcs->curvature[k], end);
            }
        if (arcs->best >= 0 && std::isfinite(arcs->curvature[static_cast<std::size_t>(arcs->best)])) {
            const auto k = static_cast<std::size_t>(arcs->best);
            const float clear = arcs->clear_distance_m[k];
            const double end = std::isfinite(clear) ? std::clamp(static_cast<double>(clear), 0.0, length) : length;
            draw_arc(img, p, m, o.cell_px, arcs->curvature[k], end, 4, false, kBestArc);
        }
    }
    draw_vehicle(img, p, m, o);
    draw_legend(img, m, arcs, o.cell_px, p.x1 + 1 + kLegendGap, kTraverseMargin);
    return img;
}

}  // namespace ugv::render
