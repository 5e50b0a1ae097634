// The egocentric map's rotation (eq. 9-18) as the report writes it, one cell at a time in
// double: the specification of EgocentricGrid::transform, whose vector kernels
// (kernels/turn_slots.cpp) compute the same in float on groups of slots and are tested
// against this.
#include <algorithm>
#include <cmath>

#include "ugv/terrain/egocentric_grid.hpp"

namespace ugv::terrain {

namespace {

// What lands in one cell of the turned map, about its centre.
struct Landed
{
    bool any = false;
    double w = 0.0;
    double wx = 0.0, wy = 0.0;    // sum w x, sum w y: x, y from the new cell's centre
    double wx2 = 0.0, wy2 = 0.0;  // sum w x^2, sum w y^2, likewise
    float z_ref_m = 0.0f;         // the first cell's reference height; the z sums about it
    double wz = 0.0, wz2 = 0.0;
    CellTally tally;  // count and extremes: merged as a rotation merges them
};

}  // namespace

int EgocentricGrid::transform_reference(double angle_rad, double pivot_x_m, double pivot_y_m,
                                        std::vector<uint8_t>* near_edge)
{
    const double c = std::cos(angle_rad), s = std::sin(angle_rad), g = grid_m_;
    std::vector<Landed> landed(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    if (near_edge) near_edge->assign(landed.size(), 0);
    int dropped = 0;
    for (int i = 0; i < nx_; ++i) {
        for (int j = 0; j < ny_; ++j) {
            const uint32_t slot = slot_[static_cast<std::size_t>(physical(i, j))];
            if (slot == kNoSlot) continue;
            const CellSums& a = pool_.sums(static_cast<int>(slot));
            const double w = a.w;
            // Eq. 9-10, 17-18: the samples' mean position is the cell's centre plus its
            // remainder; about the pivot.
            const double x = (i + 0.5) * g + a.x_wx / w - pivot_x_m;
            const double y = y_min_m_ + (j + 0.5) * g + a.y_wy / w - pivot_y_m;
            // Eq. 11-14: in the frame turned by the angle.
            const double x_new = c * x + s * y;
            const double y_new = c * y - s * x;
            // Eq. 5-7: the cell it lands in; outside the map it is dropped.
            const double fi = x_new / g, fj = (y_new - y_min_m_) / g;
            if (!(fi >= 0.0 && fi < nx_ && fj >= 0.0 && fj < ny_)) {
                ++dropped;
                continue;
            }
            const int i_new = static_cast<int>(fi), j_new = static_cast<int>(fj);
            // Eq. 15-16: the new remainder, from the new cell's centre.
            const double x_rel = x_new - (i_new + 0.5) * g;
            const double y_rel = y_new - y_min_m_ - (j_new + 0.5) * g;
            // The samples' spread about their mean turns with the frame; the x-y covariance is
            // not kept, so the two variances mix by cos^2 and sin^2.
            const double w_var_x = std::max(0.0, a.x_wx2 - static_cast<double>(a.x_wx) * a.x_wx / w);
            const double w_var_y = std::max(0.0, a.y_wy2 - static_cast<double>(a.y_wy) * a.y_wy / w);
            const int to = i_new * ny_ + j_new;  // unwrapped: the turned map has no column shift
            Landed& l = landed[static_cast<std::size_t>(to)];
            if (!l.any) {
                l.any = true;
                l.z_ref_m = a.z_ref_m;
            }
            // Cells landing together pool their sums and tallies.
            l.w += w;
            l.wx += w * x_rel;
            l.wy += w * y_rel;
            l.wx2 += w * x_rel * x_rel + c * c * w_var_x + s * s * w_var_y;
            l.wy2 += w * y_rel * y_rel + s * s * w_var_x + c * c * w_var_y;
            double wz = 0.0, wz2 = 0.0;
            z_sums_about(a, l.z_ref_m, wz, wz2);
            l.wz += wz;
            l.wz2 += wz2;
            l.tally.merge(pool_.tally(static_cast<int>(slot)));
            if (near_edge) {
                const auto close = [](double f) { return std::abs(f - std::round(f)) < 5e-3; };
                if (close(fi) || close(fj)) (*near_edge)[static_cast<std::size_t>(to)] = 1;
            }
        }
    }
    // The turned map replaces the pool, in unwrapped order, with no column shift (as
    // transform() leaves it).
    pool_.clear(0, used_);
    used_ = 0;
    free_count_ = 0;
    m_j_ = 0;
    std::fill(slot_.begin(), slot_.end(), kNoSlot);
    std::vector<uint8_t> unwrapped_edge;  // near_edge by unwrapped cell, until here
    if (near_edge) {
        unwrapped_edge.swap(*near_edge);
        near_edge->assign(landed.size(), 0);
    }
    for (int i = 0; i < nx_; ++i) {
        for (int j = 0; j < ny_; ++j) {
            const int cell = physical(i, j);
            const std::size_t k = static_cast<std::size_t>(i * ny_ + j);
            if (near_edge) (*near_edge)[static_cast<std::size_t>(cell)] = unwrapped_edge[k];
            const Landed& l = landed[k];
            if (!l.any) continue;
            const int slot = static_cast<int>(take_slot(cell));
            CellSums& sums = pool_.sums(slot);
            sums.w = static_cast<float>(l.w);
            sums.x_wx = static_cast<float>(l.wx);
            sums.y_wy = static_cast<float>(l.wy);
            sums.z_wz = static_cast<float>(l.wz);
            sums.z_ref_m = l.z_ref_m;
            sums.x_wx2 = static_cast<float>(l.wx2);
            sums.y_wy2 = static_cast<float>(l.wy2);
            sums.z_wz2 = static_cast<float>(l.wz2);
            pool_.tally(slot) = l.tally;
        }
    }
    return dropped;
}

}  // namespace ugv::terrain
