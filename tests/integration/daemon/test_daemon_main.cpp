// ugv-test-daemon: publishes a raw_bytes_t tick every period_ms on `channel`; with --replay,
// copies every message of channel IN to OUT with seq * 2 (live too with echo = true). Only
// for the runtime's tests.
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/raw_bytes_t.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-test-daemon", .status_channel = "", .processing = true}, argc, argv);
    auto& cfg = d.config();
    const std::string channel = cfg.get_string("channel", "TICK");
    const int64_t period_ms = cfg.get_int("period_ms", 50, 1, 10000);
    const bool healthy = cfg.get_bool("healthy", true);
    const bool echo = cfg.get_bool("echo", false);
    d.start();
    auto& ticks = d.counters()["ticks"];
    if (d.replaying() || echo) {
        ugv::bus::subscribe<ugv::raw_bytes_t>(d.bus(), "IN", [&](const std::string&, const ugv::raw_bytes_t& m, int64_t) {
            auto copy = m;
            copy.seq = m.seq * 2;
            ugv::bus::publish(d.out(), "OUT", copy);
        });
        if (d.replaying()) return d.run();
    }
    int64_t seq = 0;
    d.add_timer(period_ms * 1000, [&] {
        ugv::raw_bytes_t m{};
        m.utime = d.out().now_utime();
        m.seq = seq++;
        m.device = "test";
        ugv::bus::publish(d.out(), channel, m);
        ++ticks;
        if (healthy) d.mark_output();
        if (seq == 1) d.ready();
    });
    return d.run();
}
