#include "terrain_node.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include <spdlog/spdlog.h>

#include "terrain_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/input_stamps.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/whole_file.hpp"
#include "ugv/runtime/counters.hpp"
#include "ugv/runtime/rate_limited_log.hpp"
#include "ugv/terrain/map_state.hpp"
#include "ugv/terrain/simd.hpp"

namespace ugv::terrain_daemon {

namespace {

// A cloud is one scan (13-27 ms); a point offset beyond this is garbage, and must not push
// the cloud's end time past any pose (or past int64).
constexpr float kMaxCloudSpanS = 10.0f;
constexpr std::size_t kRecentClouds = 64;  // per sensor, for duplicates: ~2 s of scans
constexpr std::size_t kMaxSensors = 16;     // a vehicle has a few lasers
// Clouds lead the pose by an IMU period and a scan (~40 ms). One stamped far
// ahead would wait at the head of the queue for a pose that never comes, holding back every
// cloud behind it, and would push the publishing clock into the future: it is rejected.
constexpr int64_t kMaxCloudLeadUs = 5'000'000;
constexpr std::size_t kMaxWaitingClouds = 256;  // ~5 s of clouds from two lasers

bool leads_too_far(int64_t cloud_us, int64_t newest_pose_us)
{
    return newest_pose_us < INT64_MAX - kMaxCloudLeadUs && cloud_us > newest_pose_us + kMaxCloudLeadUs;
}

// Time of a cloud's last point (us). msg.utime > 0 (on_points).
int64_t cloud_end_us(const point_cloud_t& msg)
{
    float latest = 0.0f;
    for (float t : msg.time_offset)
        if (std::isfinite(t)) latest = std::max(latest, t);
    const int64_t span_us = std::llround(static_cast<double>(std::min(latest, kMaxCloudSpanS)) * 1e6);
    return msg.utime > INT64_MAX - span_us ? INT64_MAX : msg.utime + span_us;
}

}  // namespace

TerrainNode::TerrainNode(const TerrainConfig& config, Publish publish, std::function<int64_t()> now_us)
    : config_(config),
      mapper_(config.map),
      publish_(std::move(publish)),
      now_us_(std::move(now_us)),
      period_us_(std::llround(1e6 / config.publish_hz))
{
}

void TerrainNode::on_pose(const pose_t& msg)
{
    ++counters_.poses_in;
    if (msg.utime <= 0) {  // no time: the history and the publishing clock need one
        ++counters_.poses_rejected_time;
        return;
    }
    if (msg.status == pose_t::STATUS_INITIALIZING || msg.status == pose_t::STATUS_FAULT) {
        ++counters_.poses_rejected_status;
        return;
    }
    // A pose far after the newest one is a clock gone wrong (one message: taken, it would
    // make every later pose out of order and freeze the map) or the stream resuming after a
    // gap (the next pose agrees with it). It is held until the next pose tells which.
    if (mapper_.has_pose() && leads_too_far(msg.utime, mapper_.poses().newest_us())) {
        const bool confirms = held_jump_ && msg.utime > held_jump_->utime && !leads_too_far(msg.utime, held_jump_->utime);
        if (!confirms) {
            if (held_jump_) ++counters_.poses_rejected_time;
            held_jump_ = msg;
            return;
        }
        accept_pose(*std::exchange(held_jump_, std::nullopt));
    } else if (held_jump_) {
        ++counters_.poses_rejected_time;  // the jump was one bad message
        held_jump_.reset();
    }
    accept_pose(msg);
}

void TerrainNode::accept_pose(const pose_t& msg)
{
    if (mapper_.add_pose(to_pose(msg)) == terrain::PoseHistory::AddResult::added) {
        last_pose_ = msg;
        have_pose_ = true;
    }
    fuse_ready(false);
    maybe_publish(msg.utime);
}

void TerrainNode::on_points(const point_cloud_t& msg)
{
    ++counters_.clouds_in;
    if (msg.utime <= 0) {  // no time: nothing to place it with (and the wait arithmetic needs > 0)
        ++counters_.clouds_malformed;
        return;
    }
    // The same cloud delivered twice (a re-sent or looped-back message, or a log replayed
    // into a live bus) would be fused twice, doubling its points' weight in every cell.
    if (mapper_.has_pose() && leads_too_far(msg.utime, mapper_.poses().newest_us())) {
        ++counters_.clouds_rejected_time;
        return;
    }
    std::deque<int64_t>& recent = recent_clouds_of(msg.sensor_id);
    if (std::find(recent.begin(), recent.end(), msg.utime) != recent.end()) {
        ++counters_.clouds_duplicate;
        return;
    }
    recent.push_back(msg.utime);
    if (recent.size() > kRecentClouds) recent.pop_front();
    waiting_.push_back(msg);
    // Clouds that all carry the same time never wait "long enough" by message time: the
    // queue is bounded by count too, the oldest fused with the poses there are.
    while (waiting_.size() > kMaxWaitingClouds) {
        ++counters_.clouds_overflow;
        fuse(waiting_.front());
        waiting_.pop_front();
    }
    fuse_ready(false);
    maybe_publish(msg.utime);
}

void TerrainNode::flush()
{
    fuse_ready(true);
}

void TerrainNode::fuse(const point_cloud_t& msg)
{
    terrain::PointBatch batch;
    // A point offset beyond a scan's possible span is a bad time field: the pose lookups add
    // it to the cloud's time, which must not leave the int64 range.
    const bool offsets_ok = std::none_of(msg.time_offset.begin(), msg.time_offset.end(),
                                         [](float t) { return std::isfinite(t) && std::abs(t) > kMaxCloudSpanS; });
    if (!offsets_ok || !to_batch(msg, batch)) {
        ++counters_.clouds_malformed;
        return;
    }
    mapper_.fuse(batch);
}

void TerrainNode::fuse_ready(bool all)
{
    // A cloud is fused once a pose at or after its last point exists, or once it has waited
    // max_point_wait of message time (its late points are then counted as after_history).
    const bool has_pose = mapper_.has_pose();
    const int64_t newest = has_pose ? mapper_.poses().newest_us() : INT64_MIN;
    int64_t latest_message = newest;
    if (!waiting_.empty()) latest_message = std::max(latest_message, waiting_.back().utime);
    while (!waiting_.empty()) {
        const point_cloud_t& front = waiting_.front();
        if (has_pose && leads_too_far(front.utime, newest)) {  // it came before any pose did
            ++counters_.clouds_rejected_time;
            waiting_.pop_front();
            continue;
        }
        const bool covered = has_pose && cloud_end_us(front) <= newest;
        const bool waited = latest_message - front.utime > config_.max_point_wait_us;
        if (!(all || covered || waited)) break;
        fuse(front);
        waiting_.pop_front();
    }
}

std::deque<int64_t>& TerrainNode::recent_clouds_of(const std::string& sensor_id)
{
    auto it = recent_clouds_.find(sensor_id);
    if (it == recent_clouds_.end()) {
        if (recent_clouds_.size() >= kMaxSensors) {
            recent_clouds_.erase(std::min_element(recent_clouds_.begin(), recent_clouds_.end(), [](const auto& a, const auto& b) {
                return a.second.last_seen < b.second.last_seen;
            }));
            ++counters_.sensors_forgotten;
        }
        it = recent_clouds_.emplace(sensor_id, RecentClouds{}).first;
    }
    it->second.last_seen = ++clouds_seen_;
    return it->second.utimes;
}

void TerrainNode::maybe_publish(int64_t message_time_us)
{
    if (!have_pose_) return;
    if (next_publish_us_ == 0) next_publish_us_ = message_time_us;
    if (message_time_us < next_publish_us_) return;
    // Catch up without a burst after a gap: the next slot after this message.
    next_publish_us_ = message_time_us + (period_us_ - (message_time_us - next_publish_us_) % period_us_);
    const int64_t start = now_us_();
    map_updated_ = mapper_.counters().points_fused != fused_at_publish_;
    fused_at_publish_ = mapper_.counters().points_fused;
    mapper_.snapshot(snapshot_);
    to_message(snapshot_, last_pose_, seq_++, message_);
    publish_(message_);
    ++counters_.maps_published;
    counters_.last_publish_us = now_us_() - start;
}

namespace {

// The saved map at path, if any. A file that is not a regular file, or larger than a map of
// this layout can be, is refused unread.
std::optional<terrain::MapState> read_saved_map(const std::string& path, const terrain::MapConfig& map)
{
    std::vector<uint8_t> bytes;
    std::string why;
    switch (io::read_regular_file(path, terrain::max_encoded_size(map.nx(), map.ny()), bytes, why)) {
    case io::ReadResult::missing:
        spdlog::info("map_file {}: none saved yet, starting with an empty map", path);
        return std::nullopt;
    case io::ReadResult::ok:
        if (auto state = terrain::decode_map_state(bytes.data(), bytes.size(), why)) {
            spdlog::info("map_file {}: {} known cells saved, restored if the first pose is within the map's extent",
                         path, state->cells.size());
            return state;
        }
        break;
    case io::ReadResult::unreadable:
    case io::ReadResult::not_a_file:
    case io::ReadResult::too_large: break;
    }
    spdlog::warn("map_file {}: refused ({}); starting with an empty map", path, why);
    return std::nullopt;
}

}  // namespace

int run(daemon::Daemon& d, const TerrainConfig& config)
{
    // Flowing: maps whose content new points updated (a map republished as it was is not).
    d.declare_output("maps updated by new points on " + config.map_channel, config.health_timeout_us);
    TerrainNode* self = nullptr;
    bool any_published = false;
    // While every message of one input is refused: DEGRADED, saying which, even though maps
    // still go out (they no longer take in what the vehicle sees, or no longer move with it);
    // RUNNING again once one is taken. A pose older than the pose history is of no use, nor a
    // cloud whose poses are gone.
    daemon::InputStamps stamps(d, {.max_ahead_us = config.max_stamp_ahead_us, .max_age_us = config.map.pose_history_us, .skew = config.stamp_skew},
                               [&] {
                                   if (any_published) d.ready();
                               });
    const int pose_input = stamps.add_input(config.pose_channel);
    const int points_input = stamps.add_input(config.points_channel);
    TerrainNode node(
        config,
        [&d, &config, &self, &stamps, &any_published](const terrain_map_t& msg) {
            if (!bus::publish(d.out(), config.map_channel, msg)) return;
            if (self && self->map_updated()) d.mark_output();
            if (!any_published && !stamps.refusing()) d.ready();
            any_published = true;
        },
        [] { return io::monotonic_us(); });
    self = &node;
    const bool egocentric = config.map.mode == terrain::MapMode::egocentric;
    if (!config.map_file.empty() && !egocentric)
        spdlog::warn("map_file: the world-aligned map is not kept across restarts");
    const bool keep_map = !config.map_file.empty() && !d.replaying() && egocentric;
    MapFileCounters file_counters;
    if (keep_map) {
        if (auto saved = read_saved_map(config.map_file, config.map)) node.restore_at_first_pose(std::move(*saved));
    }
    bool restore_logged = false;
    const auto sync_counters = [&] {
        runtime::set_all(d.counters(), node.mapper().counters());
        runtime::set_all(d.counters(), node.counters());
        runtime::set_all(d.counters(), file_counters);
        const auto outcome = node.mapper().restore_outcome();
        if (restore_logged || outcome == terrain::RestoreOutcome::none || outcome == terrain::RestoreOutcome::pending)
            return;
        restore_logged = true;
        const double moved_m = node.mapper().restore_distance_m();
        if (outcome == terrain::RestoreOutcome::restored)
            spdlog::info("map restored: {} known cells, the first pose {:.1f} m from where it was saved",
                         node.mapper().counters().cells_restored, moved_m);
        else if (outcome == terrain::RestoreOutcome::moved)
            spdlog::info("saved map dropped: the first pose is {:.1f} m from it, beyond the map's extent", moved_m);
        else
            spdlog::warn("saved map dropped: another layout, statistics, reference point or mode");
    };
    // Saved only when something changed: a parked vehicle does not rewrite the file.
    uint64_t saved_version = 0;
    runtime::RateLimitedLog save_log;
    const auto save_map = [&] {
        const auto& c = node.mapper().counters();
        const uint64_t version = c.points_fused + c.wraps + c.rotations + c.recentres + c.resets + c.cells_dropped + 1;
        terrain::MapState state;
        if (version == saved_version || !node.mapper().save_state(state)) return;
        std::string why;
        const std::vector<uint8_t> bytes = terrain::encode_map_state(state);
        if (io::write_file_atomically(config.map_file, bytes.data(), bytes.size(), why)) {
            ++file_counters.map_saves;
            saved_version = version;
        } else {
            ++file_counters.map_save_failures;
            save_log.log(spdlog::level::warn, "save", "map_file: cannot save: " + why, io::monotonic_us());
        }
        sync_counters();
    };
    sync_counters();  // every counter is listed from the first status message on
    bus::subscribe<pose_t>(d.bus(), config.pose_channel, [&](const std::string&, const pose_t& m, int64_t) {
        if (!stamps.accept(pose_input, m.utime)) return;
        node.on_pose(m);
        sync_counters();
    });
    bus::subscribe<point_cloud_t>(d.bus(), config.points_channel,
                                  [&](const std::string&, const point_cloud_t& m, int64_t) {
                                      if (!stamps.accept(points_input, m.utime)) return;
                                      node.on_points(m);
                                      sync_counters();
                                  });
    if (keep_map) d.add_timer(config.map_save_period_us, save_map);
    spdlog::info("mapping {} + {} -> {} at {} Hz of message time ({} vector code){}", config.points_channel,
                 config.pose_channel, config.map_channel, config.publish_hz,
                 terrain::to_string(terrain::simd_level()), keep_map ? ", map kept in " + config.map_file : "");
    const int rc = d.run();
    if (keep_map) save_map();  // SIGTERM: the map as it stands
    sync_counters();
    const auto& c = d.counters();
    spdlog::info("{} points fused, {} maps published, {} wraps, {} rotations", c.get("points_fused"),
                 c.get("maps_published"), c.get("wraps"), c.get("rotations"));
    return rc;
}

}  // namespace ugv::terrain_daemon
