#include "device_thread.hpp"

#include <spdlog/spdlog.h>

#include "scan_message.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"

namespace ugv::lms_daemon {

namespace lms = ugv::sick_lms2xx;

DeviceThread::DeviceThread(daemon::Daemon& d, const LmsConfig& config)
    : d_(d),
      config_(config),
      published_(d.counters()["published"]),
      publish_failures_(d.counters()["publish_failures"]),
      session_(port_, config.session,
               lms::SessionCallbacks{
                   .on_scan =
                       [this](const lms::StampedScan& s) {
                           d_.mark_alive();
                           if (publish(config_.channel, to_message(s, config_.sensor_id, scan_seq_++))) ++published_;
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
    // Healthy while scans arrive well within the time after which the session gives up.
    d_.set_health_timeout_us(static_cast<int64_t>(2 * session_.silence_timeout_s() * 1e6));
}

DeviceThread::~DeviceThread() { join(); }

void DeviceThread::start()
{
    thread_ = std::thread([this] { run(); });
}

void DeviceThread::join()
{
    if (thread_.joinable()) thread_.join();
}

void DeviceThread::run()
{
    if (!port_.open(config_.device, 9600)) {
        spdlog::warn("{} (will keep trying)", port_.last_error());
        d_.set_state(daemon::State::degraded, port_.last_error());
        session_.mark_closed();
    }
    session_.run();
    port_.close();
}

bool DeviceThread::reopen()
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

void DeviceThread::on_state(lms::SessionState s, const std::string& why)
{
    streaming_ = s == lms::SessionState::streaming;
    switch (s) {
    case lms::SessionState::streaming:
        spdlog::info("streaming: {}", why);
        d_.set_state(daemon::State::running);
        break;
    case lms::SessionState::recovering:
        if (!why.empty()) log_.log(spdlog::level::warn, "recover", why, io::monotonic_us());
        if (d_.state() != daemon::State::starting) d_.set_state(daemon::State::degraded, why);
        break;
    case lms::SessionState::probing:
    case lms::SessionState::configuring:
        if (!why.empty()) spdlog::info("{}: {}", lms::to_string(s), why);
        break;
    case lms::SessionState::stopped: break;
    }
}

void DeviceThread::on_bytes(const uint8_t* data, std::size_t n, int64_t utime, bool from_device)
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
bool DeviceThread::publish(const std::string& channel, const M& m)
{
    if (bus::publish(d_.out(), channel, m)) return true;
    ++publish_failures_;
    return false;
}

void DeviceThread::publish_counters()
{
    const lms::SessionStats& s = session_.stats();
    auto& c = d_.counters();
    c["scans"] = s.scans.load();
    c["crc_errors"] = s.crc_errors.load();
    c["resyncs"] = s.resyncs.load();
    c["naks"] = s.naks.load();
    c["timeouts"] = s.timeouts.load();
    c["reconnects"] = s.reconnects.load();
    c["bytes_in"] = s.bytes_in.load();
    c["bad_scans"] = s.bad_scans.load();
    c["clock_restarts"] = s.clock_restarts.load();
}

}  // namespace ugv::lms_daemon
