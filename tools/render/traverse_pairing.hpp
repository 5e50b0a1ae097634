// Which traversability maps of a log to draw, each with the arcs of the same terrain map
// (map_seq and utime), whichever of the two comes first in the log. No I/O: the log loop
// feeds the decoded messages in log order and gets the pairs back through a callback.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>

#include <ugv/candidate_arcs_t.hpp>
#include <ugv/traversability_map_t.hpp>

namespace ugv::render {

class TraversePairing
{
public:
    // index: the map's number in the log, from 1; arcs nullptr when the log has none for it.
    // Returning false stops (e.g. a file could not be written): add_* and finish() return it.
    using Draw = std::function<bool(const traversability_map_t& map, const candidate_arcs_t* arcs, int index)>;

    // every 0: only the last map, at finish(); N: maps 1, N + 1, 2N + 1, ...
    TraversePairing(int every, Draw draw);

    bool add_map(const traversability_map_t& map);
    bool add_arcs(const candidate_arcs_t& arcs);
    // Draws what is still held (the last map; maps whose arcs never came).
    bool finish();

    int maps() const { return maps_; }
    int arcs() const { return arcs_; }
    int drawn_with_arcs() const { return with_arcs_; }
    int drawn_without_arcs() const { return without_arcs_; }

    // A chosen map waits for its arcs until this many later maps have come.
    static constexpr int kWaitMaps = 4;
    // Arcs are kept for maps that come after them: the newest this many.
    static constexpr std::size_t kKeepArcs = 16;

private:
    struct Held
    {
        traversability_map_t map;
        int index;
        int later_maps;
    };
    const candidate_arcs_t* find(const traversability_map_t& map) const;
    bool draw(const Held& h, const candidate_arcs_t* arcs);

    int every_;
    Draw draw_;
    std::deque<candidate_arcs_t> recent_arcs_;
    std::deque<Held> held_;
    int maps_ = 0, arcs_ = 0, with_arcs_ = 0, without_arcs_ = 0;
};

}  // namespace ugv::render
