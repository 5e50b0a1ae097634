// ugv-logstat: rate, size and sequence gaps per channel of an LCM log.
//   ugv-logstat LOG [--channel REGEX] [--json]
// Exit 0; 2 when the log cannot be read.
#include <cstdio>
#include <regex>

#include <CLI/CLI.hpp>

#include "ugv/bus/bus.hpp"
#include "ugv/logstat/channel_stats.hpp"

int main(int argc, char** argv)
{
    std::string log, channel = ".*";
    bool json = false;
    CLI::App app{"ugv-logstat: rate, size and sequence gaps per channel of an LCM log"};
    app.set_version_flag("--version", std::string("ugv-logstat ") + UGV_VERSION);
    app.add_option("log", log, "LCM log file")->required()->check(CLI::ExistingFile);
    app.add_option("--channel", channel, "only channels matching this regex");
    app.add_flag("--json", json, "one JSON object per channel instead of a table");
    CLI11_PARSE(app, argc, argv);

    std::unique_ptr<ugv::bus::Bus> bus;
    try {
        bus = ugv::bus::open_log_replay(log);
    } catch (const ugv::bus::BusError& e) {
        std::fprintf(stderr, "ugv-logstat: %s\n", e.what());
        return 2;
    }
    ugv::logstat::StreamStats stats;
    bus->subscribe(channel, [&](const std::string& ch, const uint8_t* d, std::size_t n, int64_t t) { stats.add(ch, d, n, t); });
    while (bus->handle(0) == ugv::bus::HandleResult::handled) {
    }
    if (!json) std::printf("%-24s %8s %9s %10s %9s %6s %12s\n", "channel", "count", "rate_hz", "max_gap_ms", "kB/msg", "seq_gaps", "seq_backwards");
    for (const auto& [ch, s] : stats.channels()) {
        const double kb = s.count ? static_cast<double>(s.bytes) / static_cast<double>(s.count) / 1024.0 : 0.0;
        if (json)
            std::printf("{\"channel\":\"%s\",\"count\":%lld,\"rate_hz\":%.3f,\"max_interval_ms\":%.1f,\"bytes_per_msg\":%.0f,"
                        "\"seq_gaps\":%lld,\"seq_backwards\":%lld}\n",
                        ch.c_str(), static_cast<long long>(s.count), s.rate_hz(), static_cast<double>(s.max_interval_us) / 1e3,
                        kb * 1024.0, static_cast<long long>(s.seq_gaps), static_cast<long long>(s.seq_backwards));
        else
            std::printf("%-24s %8lld %9.2f %10.1f %9.2f %6lld %12lld\n", ch.c_str(), static_cast<long long>(s.count), s.rate_hz(),
                        static_cast<double>(s.max_interval_us) / 1e3, kb, static_cast<long long>(s.seq_gaps),
                        static_cast<long long>(s.seq_backwards));
    }
    return 0;
}
