#include "traverse_node.hpp"

#include <exception>
#include <stdexcept>
#include <utility>

#include <sys/eventfd.h>
#include <unistd.h>

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include "traverse_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/input_stamps.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/runtime/counters.hpp"
#include "ugv/runtime/rate_limited_log.hpp"

namespace ugv::traverse_daemon {

TraverseNode::TraverseNode(const TraverseConfig& config, PublishArcs arcs, PublishMap map,
                           std::function<int64_t()> now_us)
    : config_(config),
      analysis_(config.analysis),
      publish_arcs_(std::move(arcs)),
      publish_map_(std::move(map)),
      now_us_(std::move(now_us))
{
}

bool TraverseNode::on_map(const terrain_map_t& msg)
{
    to_grid(msg, grid_);
    const int64_t start = now_us_();
    bool ok = false;
    try {
        ok = analysis_.update(grid_);
        why_ = ok ? std::string() : analysis_.why();
    } catch (const std::exception& e) {  // never through the bus callback
        ++counters_.update_errors;
        why_ = std::string("the analysis failed: ") + e.what();
    }
    counters_.update_time_us = now_us_() - start;
    if (!ok) return false;
    const int64_t publish_start = now_us_();
    const traverse::TraverseResult& r = analysis_.result();
    to_message(r, config_.analysis, msg, seq_, arcs_msg_);
    publish_arcs_(arcs_msg_);
    to_message(r.layers, msg, seq_, map_msg_);
    publish_map_(map_msg_);
    ++seq_;
    ++counters_.maps_published;
    counters_.publish_time_us = now_us_() - publish_start;
    return true;
}

void TraverseNode::keep(const terrain_map_t& msg)
{
    if (kept_) ++counters_.maps_skipped;
    kept_map_ = msg;
    kept_ = true;
}

int run(daemon::Daemon& d, const TraverseConfig& config)
{
    // Flowing: ARCS published, i.e. maps come and are analysed (malformed ones are not).
    d.declare_output(config.arcs_channel, config.health_timeout_us);
    bool any_published = false;
    int64_t last_published_us = io::monotonic_us();  // or the start
    bool dropping = false;  // DEGRADED because every map is dropped
    // While every map is refused for its stamp: DEGRADED, saying so; RUNNING again once one
    // is taken. A map older than max_age_s would be all UNKNOWN.
    daemon::InputStamps stamps(d, {.max_ahead_us = config.max_stamp_ahead_us, .max_age_us = config.max_stamp_age_us, .skew = config.stamp_skew},
                               [&] {
                                   if (any_published) d.ready();
                               });
    const int map_input = stamps.add_input(config.map_channel);
    TraverseNode node(
        config,
        [&](const candidate_arcs_t& m) {
            if (!bus::publish(d.out(), config.arcs_channel, m)) return;
            d.mark_output();
            last_published_us = io::monotonic_us();
            if ((!any_published || dropping) && !stamps.refusing()) d.ready();
            dropping = false;
            any_published = true;
        },
        [&](const traversability_map_t& m) { bus::publish(d.out(), config.traversability_channel, m); },
        [] { return io::monotonic_us(); });
    const auto sync_counters = [&] {
        runtime::set_all(d.counters(), node.analysis().counters());
        runtime::set_all(d.counters(), node.counters());
    };
    sync_counters();  // every counter is listed from the first status message on
    runtime::RateLimitedLog dropped_log;
    const auto analyse = [&](const terrain_map_t& m) {
        if (!node.on_map(m)) {
            const std::string why = "map seq " + std::to_string(m.seq) + " dropped: " + node.why();
            dropped_log.log(spdlog::level::warn, "dropped", config.map_channel + " " + why, io::monotonic_us());
            // Maps come but none gets through: DEGRADED with the library's reason (the daemon
            // is alive and saying why; a restart would not help), RUNNING with the next ARCS.
            const double stalled_s = static_cast<double>(io::monotonic_us() - last_published_us) * 1e-6;
            if (stalled_s * 1e6 > static_cast<double>(config.health_timeout_us) && !stamps.refusing()) {
                d.set_state(daemon::State::degraded, fmt::format("no map analysed for {:.1f} s, {}", stalled_s, why));
                dropping = true;
            }
        }
        sync_counters();
    };
    // Live, a map is kept and analysed once the bus has been read (the event fd wakes the
    // loop right after): maps that queued up meanwhile replace it, and only the newest is
    // analysed. A replay analyses every map, in order.
    const int wake_fd = d.replaying() ? -1 : ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (!d.replaying() && wake_fd < 0) throw std::runtime_error("eventfd failed");
    if (wake_fd >= 0)
        d.add_fd(wake_fd, [&] {
            uint64_t n = 0;
            (void)!::read(wake_fd, &n, sizeof n);
            if (node.has_kept()) analyse(node.take_kept());
        });
    bus::subscribe<terrain_map_t>(d.bus(), config.map_channel, [&](const std::string&, const terrain_map_t& m, int64_t) {
        if (!stamps.accept(map_input, m.utime)) return;
        if (wake_fd < 0) {
            analyse(m);
            return;
        }
        node.keep(m);
        const uint64_t one = 1;
        (void)!::write(wake_fd, &one, sizeof one);
    });
    const traverse::ArcSetConfig& a = config.analysis.arcs;
    spdlog::info("analysing {} -> {} + {} ({} arcs of |curvature| <= {} /m, {} m long, unknown cells {})",
                 config.map_channel, config.traversability_channel, config.arcs_channel, a.count,
                 a.max_curvature_per_m, a.length_m,
                 a.unknown_policy == traverse::UnknownPolicy::cautious ? "cautious" : "optimistic");
    const int rc = d.run();
    if (wake_fd >= 0) ::close(wake_fd);
    sync_counters();
    const auto& c = d.counters();
    spdlog::info("{} maps in, {} published, {} malformed, {} duplicates", c.get("maps_in"), c.get("maps_published"),
                 c.get("maps_malformed"), c.get("maps_duplicate"));
    return rc;
}

}  // namespace ugv::traverse_daemon
