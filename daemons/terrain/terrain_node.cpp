#include "terrain_node.hpp"

#include <algorithm>
#include <cmath>

#include "lcm_convert.hpp"

namespace ugv::terrain_daemon {

namespace {

// Time of a cloud's last point (us).
int64_t cloud_end_us(const point_cloud_t& msg)
{
    float latest = 0.0f;
    for (float t : msg.time_offset)
        if (std::isfinite(t)) latest = std::max(latest, t);
    return msg.utime + std::llround(static_cast<double>(latest) * 1e6);
}

}  // namespace

TerrainNode::TerrainNode(const TerrainDaemonConfig& config, Publish publish, std::function<int64_t()> now_us)
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
    if (msg.status == pose_t::STATUS_INITIALIZING || msg.status == pose_t::STATUS_FAULT) {
        ++counters_.poses_rejected_status;
        return;
    }
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
    // The same cloud delivered twice (a re-sent or looped-back message) would be fused twice,
    // doubling its points' weight in every cell it touches.
    const auto [last, first_of_sensor] = last_cloud_utime_.try_emplace(msg.sensor_id, msg.utime);
    if (!first_of_sensor) {
        if (last->second == msg.utime) {
            ++counters_.clouds_duplicate;
            return;
        }
        last->second = msg.utime;
    }
    waiting_.push_back(msg);
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
    if (!to_batch(msg, batch)) {
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
        const bool covered = has_pose && cloud_end_us(front) <= newest;
        const bool waited = latest_message - front.utime > config_.max_point_wait_us;
        if (!(all || covered || waited)) break;
        fuse(front);
        waiting_.pop_front();
    }
}

void TerrainNode::maybe_publish(int64_t message_time_us)
{
    if (!have_pose_) return;
    if (next_publish_us_ == 0) next_publish_us_ = message_time_us;
    if (message_time_us < next_publish_us_) return;
    // Catch up without a burst after a gap: the next slot after this message.
    while (next_publish_us_ <= message_time_us) next_publish_us_ += period_us_;
    const int64_t start = now_us_();
    mapper_.snapshot(snapshot_);
    to_message(snapshot_, last_pose_, seq_++, message_);
    publish_(message_);
    ++counters_.maps_published;
    counters_.last_publish_us = now_us_() - start;
}

}  // namespace ugv::terrain_daemon
