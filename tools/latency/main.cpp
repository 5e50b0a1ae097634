// ugv-latency: how long from an event to the message it caused, p50/p99/max, on live traffic.
//   ugv-latency --from RAW_LMS --to LMS_SCAN --for 10     last telegram byte -> scan on LCM
//   ugv-latency --to SERVO_STATE --for 10                 receive stamp (utime) -> on LCM
//   ugv-latency --from IMU --from-recv --to POSE --for 10 IMU on LCM -> POSE on LCM
//   --fifo 60 --lock-memory: measure from a real-time process, so that the measuring end's
//   own scheduling delay does not land in the figures of a real-time daemon.
// Exit 0 with one line of figures; 1 when nothing could be measured; 2 for bad arguments.
#include <cstdio>

#include <CLI/CLI.hpp>

#include "ugv/bus/bus.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/latency/latency_meter.hpp"
#include "ugv/logstat/channel_stats.hpp"
#include "ugv/runtime/realtime.hpp"
#include "ugv/runtime/stop_signals.hpp"

int main(int argc, char** argv)
{
    std::string url, from, to;
    double seconds = 10;
    bool from_recv = false;
    CLI::App app{"ugv-latency: event -> message latency on live LCM traffic"};
    app.set_version_flag("--version", std::string("ugv-latency ") + UGV_VERSION);
    app.add_option("--to", to, "channel whose messages' receive times end each measurement")->required();
    app.add_option("--from", from, "channel whose latest message starts it (default: the --to message's own utime)");
    app.add_flag("--from-recv", from_recv, "start at the --from message's receive time, not its utime field");
    app.add_option("--for", seconds, "seconds to measure")->check(CLI::PositiveNumber);
    app.add_option("--lcm-url", url, "LCM URL (default LCM_DEFAULT_URL, else udpm ttl=0)");
    ugv::runtime::RealtimeOptions rt;
    app.add_option("--fifo", rt.fifo_priority, "run SCHED_FIFO at this priority (1-99; 0 = no)")->check(CLI::Range(0, 99));
    app.add_flag("--lock-memory", rt.lock_memory, "mlockall before measuring");
    CLI11_PARSE(app, argc, argv);
    for (const std::string& w : ugv::runtime::apply_realtime(rt)) std::fprintf(stderr, "ugv-latency: %s\n", w.c_str());
    std::unique_ptr<ugv::bus::Bus> bus;
    try {
        bus = ugv::bus::open_live(url.empty() ? ugv::bus::default_url() : url);
    } catch (const ugv::bus::BusError& e) {
        std::fprintf(stderr, "ugv-latency: %s\n", e.what());
        return 2;
    }
    ugv::latency::LatencyMeter meter;
    if (!from.empty())
        bus->subscribe(from, [&](const std::string&, const uint8_t* d, std::size_t n, int64_t recv) {
            int64_t utime = 0, seq = 0;
            if (from_recv) meter.on_from(recv);
            else if (ugv::logstat::read_header(d, n, utime, seq)) meter.on_from(utime);
        });
    bus->subscribe(to, [&](const std::string&, const uint8_t* d, std::size_t n, int64_t recv) {
        int64_t utime = 0, seq = 0;
        if (from.empty()) {
            if (ugv::logstat::read_header(d, n, utime, seq)) meter.on_to(recv, utime);
        } else {
            meter.on_to(recv);
        }
    });
    ugv::runtime::install_stop_signals();
    const int64_t end = ugv::io::monotonic_us() + static_cast<int64_t>(seconds * 1e6);
    while (!ugv::runtime::stop_requested() && ugv::io::monotonic_us() < end) bus->handle(20);
    const auto s = meter.summary();
    std::printf("%s -> %s: %zu samples, latency p50 %.0f us, p99 %.0f us, max %.0f us, min %.0f us\n",
                from.empty() ? (to + ".utime").c_str() : from.c_str(), to.c_str(), s.samples, s.p50_us, s.p99_us, s.max_us,
                s.min_us);
    return s.samples > 0 ? 0 : 1;
}
