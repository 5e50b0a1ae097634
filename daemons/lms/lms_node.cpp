#include "lms_node.hpp"

#include <spdlog/spdlog.h>

#include "lms_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/runtime/counters.hpp"

namespace ugv::lms_daemon {

namespace lms = ugv::sick_lms2xx;

LmsNode::LmsNode(daemon::Daemon& d, const LmsConfig& config)
    : d_(d),
      config_(config),
      published_(d.counters()["published"]),
      publish_failures_(d.counters()["publish_failures"]),
      session_(port_, config.session,
               lms::SessionCallbacks{
                   .on_scan =
                       [this](const lms::StampedScan& s) {
                           if (!publish(config_.channel, to_message(s, config_.sensor_id, scan_seq_++))) return;
                           ++published_;
                           d_.mark_output();
                       },
                   .on_state = [this](lms::SessionState s, const std::string& why) { on_state(s, why); },
                   .on_bytes = config.publish_raw
                                   ? std::function<void(const uint8_t*, std::size_t, int64_t, bool)>(
                                         [this](const uint8_t* p, std::size_t n, int64_t t, bool from) { on_bytes(p, n, t, from); })
                                   : nullptr,
                   .reopen = [this] { return reopen(); },
                   .stop_requested = [this] { return d_.stop_requested(); },
                   .monotonic_us = [] { return io::monotonic_us(); },
                   .sleep_us = nullptr,
               })
{
    // Flowing: scans published, well within the time after which the session gives up.
    d_.declare_output("scans on " + config_.channel, static_cast<int64_t>(2 * session_.silence_timeout_s() * 1e6));
}

LmsNode::~LmsNode() { join(); }

void LmsNode::start()
{
    thread_ = std::thread([this] { run(); });
}

void LmsNode::join()
{
    if (thread_.joinable()) thread_.join();
}

void LmsNode::run()
{
    if (!port_.open(config_.device, 9600)) {
        spdlog::warn("{} (will keep trying)", port_.last_error());
        d_.set_state(daemon::State::degraded, port_.last_error());
        session_.mark_closed();
    }
    session_.run();
    port_.close();
}

bool LmsNode::reopen()
{
    port_.close();
    if (port_.open(config_.device, 9600)) {
        spdlog::info("{}: opened again", config_.device);
        return true;
    }
    log_.log(spdlog::level::warn, "open", port_.last_error(), io::monotonic_us());
    d_.set_state(daemon::State::degraded, port_.last_error());
    return false;
}

void LmsNode::on_state(lms::SessionState s, const std::string& why)
{
    streaming_ = s == lms::SessionState::streaming;
    switch (s) {
    case lms::SessionState::streaming:
        spdlog::info("streaming: {}", why);
        ever_streamed_ = true;
        d_.set_state(daemon::State::running);  // RUNNING once scans are published
        break;
    case lms::SessionState::recovering:
        if (!why.empty()) log_.log(spdlog::level::warn, "recover", why, io::monotonic_us());
        // Before the first stream the reason waits for the start-up deadline.
        d_.set_state(ever_streamed_ ? daemon::State::degraded : daemon::State::starting, why);
        break;
    case lms::SessionState::probing:
    case lms::SessionState::configuring:
        if (!why.empty()) spdlog::info("{}: {}", lms::to_string(s), why);
        break;
    case lms::SessionState::stopped: break;
    }
}

void LmsNode::on_bytes(const uint8_t* data, std::size_t n, int64_t utime, bool from_device)
{
    ugv::raw_bytes_t m;
    m.utime = utime != 0 ? utime : io::now_utime();
    m.seq = raw_seq_++;
    m.device = config_.sensor_id;
    m.direction = from_device ? ugv::raw_bytes_t::DIRECTION_FROM_DEVICE : ugv::raw_bytes_t::DIRECTION_TO_DEVICE;
    m.nbytes = static_cast<int32_t>(n);
    m.data.assign(data, data + n);
    publish(config_.raw_channel, m);
}

template <typename M>
bool LmsNode::publish(const std::string& channel, const M& m)
{
    if (bus::publish(d_.out(), channel, m)) return true;
    ++publish_failures_;
    return false;
}

void LmsNode::publish_counters() { runtime::set_all(d_.counters(), session_.stats()); }

int run(daemon::Daemon& d, const LmsConfig& config)
{
    LmsNode device(d, config);
    device.publish_counters();  // every counter is listed from the first status message on
    int ticks = 0;
    d.add_timer(200'000, [&] {
        device.publish_counters();
        if (device.streaming()) d.ready();
        if (++ticks % 5 != 0) return;  // the systemd status line once a second
        d.notify_status(device.streaming() ? "streaming, " + std::to_string(d.counters().get("scans")) + " scans"
                                           : "looking for the LMS on " + config.device);
    });
    spdlog::info("{} at {} baud, {} deg / {} deg, {} -> {}", config.device, config.session.baud,
                 config.session.angle_deg, config.session.resolution_cdeg / 100.0,
                 config.session.units == sick_lms2xx::Units::mm ? "mm" : "cm", config.channel);
    device.start();
    const int rc = d.run();
    d.request_stop();
    device.join();
    return rc;
}

}  // namespace ugv::lms_daemon
