// The mapper driven by messages: poses move the map, point clouds wait (up to
// max_point_wait) for a pose at or after their last point and are then fused, and the map
// is published every 1/publish_hz of message time (never the wall clock), so a replay
// gives the same maps as the live run, at any speed.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include <ugv/point_cloud_t.hpp>
#include <ugv/pose_t.hpp>
#include <ugv/terrain_map_t.hpp>

#include "terrain_config.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/terrain/terrain_mapper.hpp"

namespace ugv::terrain_daemon {

struct NodeCounters
{
    uint64_t poses_in = 0;
    uint64_t poses_rejected_status = 0;  // INITIALIZING or FAULT
    uint64_t clouds_in = 0;
    uint64_t clouds_malformed = 0;       // array sizes disagree with npoints, no time (utime <= 0), a point offset > 10 s
    uint64_t clouds_rejected_time = 0;   // more than kMaxCloudLeadUs after the newest pose: a bad clock
    uint64_t poses_rejected_time = 0;    // utime <= 0, or a jump of > 5 s the next pose did not confirm
    uint64_t clouds_duplicate = 0;       // same sensor and utime as that sensor's last cloud
    uint64_t clouds_overflow = 0;        // more than 256 waiting: the oldest fused with what there is
    uint64_t sensors_forgotten = 0;      // a 17th sensor id: the one heard from longest ago forgotten
    uint64_t maps_published = 0;
    int64_t last_publish_us = 0;         // wall time of the last snapshot + encode + publish

    template <class F>
    void visit(F&& f) const
    {
        f("poses_in", poses_in);
        f("poses_rejected_status", poses_rejected_status);
        f("clouds_in", clouds_in);
        f("clouds_malformed", clouds_malformed);
        f("clouds_rejected_time", clouds_rejected_time);
        f("poses_rejected_time", poses_rejected_time);
        f("clouds_duplicate", clouds_duplicate);
        f("clouds_overflow", clouds_overflow);
        f("sensors_forgotten", sensors_forgotten);
        f("maps_published", maps_published);
        f("publish_time_us", last_publish_us);
    }
};

// The map file (docs/terrain.md, "Restarts").
struct MapFileCounters
{
    uint64_t map_saves = 0;
    uint64_t map_save_failures = 0;

    template <class F>
    void visit(F&& f) const
    {
        f("map_saves", map_saves);
        f("map_save_failures", map_save_failures);
    }
};

class TerrainNode
{
public:
    using Publish = std::function<void(const terrain_map_t&)>;
    // now_us: a clock for the publish-time counter only (never used for the output).
    TerrainNode(const TerrainConfig& config, Publish publish, std::function<int64_t()> now_us);

    void on_pose(const pose_t& msg);
    void on_points(const point_cloud_t& msg);
    // Fuses every waiting cloud (end of a replay).
    void flush();

    const terrain::TerrainMapper& mapper() const { return mapper_; }
    const NodeCounters& counters() const { return counters_; }
    // A saved map, restored or dropped at the first pose (TerrainMapper::restore_at_first_pose).
    void restore_at_first_pose(terrain::MapState state) { mapper_.restore_at_first_pose(std::move(state)); }
    // Whether the last map published holds points fused since the one before: what makes
    // the daemon's output flow (a map republished unchanged does not).
    bool map_updated() const { return map_updated_; }

private:
    void fuse(const point_cloud_t& msg);
    void fuse_ready(bool all);
    void accept_pose(const pose_t& msg);
    void maybe_publish(int64_t message_time_us);

    TerrainConfig config_;
    terrain::TerrainMapper mapper_;
    Publish publish_;
    std::function<int64_t()> now_us_;
    NodeCounters counters_;
    std::deque<point_cloud_t> waiting_;
    // The times of each sensor's recent clouds (by sensor_id, newest last): a cloud whose
    // time is among them is a duplicate, even when it comes back after newer ones. At most
    // kMaxSensors ids are kept, so clouds with random ids cannot grow it.
    struct RecentClouds
    {
        std::deque<int64_t> utimes;
        uint64_t last_seen = 0;
    };
    std::deque<int64_t>& recent_clouds_of(const std::string& sensor_id);
    std::map<std::string, RecentClouds> recent_clouds_;
    uint64_t clouds_seen_ = 0;
    pose_t last_pose_{};
    bool have_pose_ = false;
    std::optional<pose_t> held_jump_;  // a pose > 5 s after the newest, until the next one
    int64_t period_us_;
    int64_t next_publish_us_ = 0;
    int64_t seq_ = 0;
    uint64_t fused_at_publish_ = 0;
    bool map_updated_ = false;
    terrain::MapSnapshot snapshot_;
    terrain_map_t message_;
};

// The daemon: a TerrainNode on the bus (subscriptions, publication, counters) until a stop
// signal, or the end of the --replay log.
int run(daemon::Daemon& d, const TerrainConfig& config);

}  // namespace ugv::terrain_daemon
