#include "traverse_pairing.hpp"

#include <utility>

#include "traverse_render.hpp"

namespace ugv::render {

TraversePairing::TraversePairing(int every, Draw draw) : every_(every), draw_(std::move(draw)) {}

const candidate_arcs_t* TraversePairing::find(const traversability_map_t& map) const
{
    for (auto it = recent_arcs_.rbegin(); it != recent_arcs_.rend(); ++it)
        if (same_terrain_map(map, *it)) return &*it;
    return nullptr;
}

bool TraversePairing::draw(const Held& h, const candidate_arcs_t* arcs)
{
    ++(arcs ? with_arcs_ : without_arcs_);
    return draw_(h.map, arcs, h.index);
}

bool TraversePairing::add_map(const traversability_map_t& map)
{
    ++maps_;
    if (every_ <= 0) {
        held_.clear();  // only the last is drawn
        held_.push_back({map, maps_, 0});
        return true;
    }
    bool ok = true;
    // Those still waiting give up after kWaitMaps later maps.
    for (auto it = held_.begin(); it != held_.end();) {
        if (++it->later_maps > kWaitMaps) {
            ok = draw(*it, nullptr) && ok;
            it = held_.erase(it);
        } else {
            ++it;
        }
    }
    if ((maps_ - 1) % every_ != 0) return ok;
    if (const candidate_arcs_t* arcs = find(map)) return draw({map, maps_, 0}, arcs) && ok;
    held_.push_back({map, maps_, 0});
    return ok;
}

bool TraversePairing::add_arcs(const candidate_arcs_t& arcs)
{
    ++arcs_;
    recent_arcs_.push_back(arcs);
    if (recent_arcs_.size() > kKeepArcs) recent_arcs_.pop_front();
    if (every_ <= 0) return true;  // the last map is drawn at finish()
    bool ok = true;
    for (auto it = held_.begin(); it != held_.end();) {
        if (same_terrain_map(it->map, arcs)) {
            ok = draw(*it, &recent_arcs_.back()) && ok;
            it = held_.erase(it);
        } else {
            ++it;
        }
    }
    return ok;
}

bool TraversePairing::finish()
{
    bool ok = true;
    for (const Held& h : held_) ok = draw(h, find(h.map)) && ok;
    held_.clear();
    return ok;
}

}  // namespace ugv::render
