// The analysis driven by messages: each TERRAIN_MAP is converted, analysed, and its
// traversability map and candidate arcs published (ARCS first: what a planner waits for).
// Nothing depends on the wall clock but the update-time counters, so a replay gives the
// same outputs as the live run, at any speed.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <ugv/candidate_arcs_t.hpp>
#include <ugv/terrain_map_t.hpp>
#include <ugv/traversability_map_t.hpp>

#include "traverse_config.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/traverse/traversability.hpp"

namespace ugv::traverse_daemon {

struct NodeCounters
{
    uint64_t maps_published = 0;   // maps analysed and published (TRAVERSABILITY_MAP and ARCS each)
    uint64_t update_errors = 0;    // the analysis threw (a bug): the map dropped, the daemon goes on
    uint64_t maps_skipped = 0;     // replaced by a newer map before their turn: never analysed
    int64_t update_time_us = 0;    // wall time of the last analysis (Traversability::update)
    int64_t publish_time_us = 0;   // wall time of the last conversion + encode + publish of both

    template <class F>
    void visit(F&& f) const
    {
        f("maps_published", maps_published);
        f("update_errors", update_errors);
        f("maps_skipped", maps_skipped);
        f("update_time_us", update_time_us);
        f("publish_time_us", publish_time_us);
    }
};

class TraverseNode
{
public:
    using PublishArcs = std::function<void(const candidate_arcs_t&)>;
    using PublishMap = std::function<void(const traversability_map_t&)>;
    // now_us: a clock for the time counters only (never used for the output).
    TraverseNode(const TraverseConfig& config, PublishArcs arcs, PublishMap map, std::function<int64_t()> now_us);

    // Analyses one map and publishes its outputs; false when the map was dropped (malformed,
    // a repeat of the last: counted by the analysis, why() says which check failed).
    bool on_map(const terrain_map_t& msg);
    // Live: keeps the map for process(). A map kept and not yet analysed is replaced and
    // counted (maps_skipped): of the maps that queued up while the daemon was busy, only the
    // newest is analysed, and its ARCS are not late behind the older ones.
    void keep(const terrain_map_t& msg);
    bool has_kept() const { return kept_; }
    // The kept map, no longer kept (valid until the next keep()); for on_map.
    const terrain_map_t& take_kept()
    {
        kept_ = false;
        return kept_map_;
    }

    const traverse::Traversability& analysis() const { return analysis_; }
    const NodeCounters& counters() const { return counters_; }
    const std::string& why() const { return why_; }

private:
    TraverseConfig config_;
    traverse::Traversability analysis_;
    PublishArcs publish_arcs_;
    PublishMap publish_map_;
    std::function<int64_t()> now_us_;
    NodeCounters counters_;
    std::string why_;
    int64_t seq_ = 0;
    traverse::TerrainGrid grid_;
    terrain_map_t kept_map_;
    bool kept_ = false;
    candidate_arcs_t arcs_msg_;
    traversability_map_t map_msg_;
};

// The daemon: a TraverseNode on the bus (subscription, publications, counters, state) until
// a stop signal, or the end of the --replay log.
int run(daemon::Daemon& d, const TraverseConfig& config);

}  // namespace ugv::traverse_daemon
