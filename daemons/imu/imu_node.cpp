#include "imu_node.hpp"

#include <chrono>
#include <thread>

#include <spdlog/spdlog.h>

#include "imu_messages.hpp"
#include "ugv/io/tap_stream.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/raw_bytes.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/serial_port.hpp"
#include "ugv/runtime/backoff.hpp"
#include "ugv/runtime/counters.hpp"
#include "ugv/runtime/rate_limited_log.hpp"

namespace ugv::imu_daemon {

namespace gx1 = ugv::microstrain_gx1;

ImuNode::ImuNode(daemon::Daemon& daemon, const ImuConfig& config)
    : d_(daemon),
      config_(config),
      published_(daemon.counters()["published"]),
      publish_failures_(daemon.counters()["publish_failures"])
{
    // Every counter exists from the start, so the status lists them all at zero.
    runtime::set_all(d_.counters(), gx1::ParserCounters{});
    runtime::set_all(d_.counters(), gx1::SessionCounters{});
    d_.counters()["reconnects"];
    // Flowing: samples published, none missing for longer than the session's silence timeout.
    d_.declare_output("samples on " + config_.channel, int64_t{config_.session.silence_timeout_ms} * 1000);
}

void ImuNode::sleep_us(int64_t us) const
{
    const int64_t end = io::monotonic_us() + us;
    while (!d_.stop_requested() && io::monotonic_us() < end)
        std::this_thread::sleep_for(std::chrono::microseconds(std::min<int64_t>(50'000, end - io::monotonic_us())));
}

void ImuNode::sync_counters(const gx1::Session& session)
{
    // The parser's counters are cumulative over the session's life: mirror them.
    runtime::set_all(d_.counters(), session.parser_counters());
    runtime::set_all(d_.counters(), session.counters());
}

void ImuNode::run()
{
    io::SerialPort port;
    io::TapStream::Tap tap;
    if (config_.publish_raw) {
        tap = [this](bool to_device, const uint8_t* data, std::size_t n, int64_t utime) {
            const auto raw = daemon::raw_bytes_message("imu", to_device, data, n, utime != 0 ? utime : io::now_utime(),
                                                       raw_seq_++);
            if (!bus::publish(d_.out(), config_.raw_channel, raw)) ++publish_failures_;
        };
    }
    io::TapStream stream(port, tap);
    gx1::Session session(stream, config_.session, gx1::FrameConverter(config_.r_body_sensor, config_.declination_rad));
    session.set_abort([this] { return d_.stop_requested(); });
    // At most 1 s between attempts: a unit that comes back streams again within ~1.5 s.
    runtime::Backoff backoff(100'000, 1'000'000);
    runtime::RateLimitedLog rlog;
    bool ever_opened = false;    // a reopen after this counts as a reconnect
    bool ever_streamed = false;  // before the first good handshake the daemon is STARTING
    const auto sigma = static_cast<float>(config_.orientation_sigma_rad);

    auto degrade = [&](const std::string& why) {
        d_.set_state(ever_streamed ? daemon::State::degraded : daemon::State::starting, why);
        rlog.log(spdlog::level::warn, why, why, io::monotonic_us());
    };
    auto on_sample = [&](const gx1::Sample& s) {
        if (bus::publish(d_.out(), config_.channel, to_message(s, seq_++, sigma))) {
            ++published_;
            d_.mark_output();
        } else {
            ++publish_failures_;
        }
    };

    while (!d_.stop_requested()) {
        if (!port.is_open()) {
            if (!port.open(config_.device, config_.baud)) {
                degrade(port.last_error());
                sleep_us(backoff.next());
                continue;
            }
            if (ever_opened) ++d_.counters()["reconnects"];
            ever_opened = true;
            spdlog::info("{} open at {} baud", config_.device, config_.baud);
        }
        if (!session.streaming()) {
            const auto st = session.initialise();
            sync_counters(session);
            if (d_.stop_requested()) break;
            if (st != gx1::Session::Status::ok) {
                // A unit set to another rate is heard as garbage: no reply ever verifies, so
                // a failed handshake names the rate it was tried at.
                degrade(st == gx1::Session::Status::failed
                            ? session.error() + " at " + std::to_string(config_.baud) + " baud on " + config_.device +
                                  " (is the unit set to another baud rate? check `baud`)"
                            : session.error());
                if (st == gx1::Session::Status::closed) port.close();
                sleep_us(backoff.next());
                continue;
            }
            backoff.reset();
            ever_streamed = true;
            const auto& info = session.info();
            spdlog::info("3DM-GX1 serial {} firmware {}: gains gyro {} accel {} mag {}, tick {:.4f} ms, {} 0x{:02X}",
                         info.serial_number, info.firmware_version, info.gains.gyro, info.gains.accel, info.gains.mag,
                         info.tick_period_s * 1e3, config_.session.continuous ? "streaming" : "polling",
                         config_.session.command);
            d_.ready();
            d_.notify_status("streaming from " + config_.device);
        }
        const auto st = session.step(100, on_sample);
        sync_counters(session);
        if (st == gx1::Session::Status::closed) {
            port.close();
            degrade(session.error());
        } else if (st == gx1::Session::Status::silence) {
            degrade(session.error());
        }
    }
    port.close();
}

int run(daemon::Daemon& d, const ImuConfig& config)
{
    ImuNode node(d, config);
    std::thread device([&node] { node.run(); });
    const int rc = d.run();
    d.request_stop();
    device.join();
    return rc;
}

}  // namespace ugv::imu_daemon
