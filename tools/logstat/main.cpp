// ugv-logstat: rate, size and sequence gaps per channel of an LCM log.
//   ugv-logstat LOG [--channel REGEX] [--json]
//   ugv-logstat LOG --scan-to-map [--scan-channel LMS_SCAN] [--map-channel TERRAIN_MAP]
//       latency from each laser scan to the first map holding its points (scan_to_map.hpp)
//   ugv-logstat LOG --latency-from TERRAIN_MAP --latency-to ARCS
//       the latency a daemon adds: each output to the input of the same utime (stamp_latency.hpp)
// Exit 0; 2 when the log cannot be read.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <regex>

#include <CLI/CLI.hpp>

#include "ugv/bus/bus.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/logstat/channel_stats.hpp"
#include "ugv/logstat/scan_to_map.hpp"
#include "ugv/logstat/stamp_latency.hpp"

namespace {

// A channel name as a JSON string body: a log's channel names are whatever was published.
std::string json_escaped(const std::string& s)
{
    std::string out;
    for (const char c : s) {
        const auto u = static_cast<unsigned char>(c);
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (u < 0x20 || u == 0x7f) {
            char b[8];
            std::snprintf(b, sizeof b, "\\u%04x", u);
            out += b;
        } else {
            out += c;
        }
    }
    return out;
}

// Seconds from a scan's utime to its last measured beam: with interlaced sweeps that is in
// the last sweep, not necessarily the last index (laser_scan_t's beam time).
double last_beam_offset_s(const ugv::laser_scan_t& s)
{
    const int n = std::max(0, s.nranges);
    const int sweeps = s.nsweeps > 1 && static_cast<int>(s.sweep_order.size()) == s.nsweeps ? s.nsweeps : 1;
    double span = 0.0;
    for (int i = std::max(0, n - sweeps); i < n; ++i) {
        int k = 0;
        for (int q = 0; q < sweeps; ++q)
            if (sweeps > 1 && s.sweep_order[static_cast<std::size_t>(q)] == i % sweeps) k = q;
        span = std::max(span, k * static_cast<double>(s.sweep_period) + i * static_cast<double>(s.time_increment));
    }
    return span;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string log, channel = ".*";
    bool json = false;
    CLI::App app{"ugv-logstat: rate, size and sequence gaps per channel of an LCM log"};
    app.set_version_flag("--version", std::string("ugv-logstat ") + UGV_VERSION);
    app.add_option("log", log, "LCM log file")->required()->check(CLI::ExistingFile);
    app.add_option("--channel", channel, "only channels matching this regex");
    app.add_flag("--json", json, "one JSON object per channel instead of a table");
    bool scan_to_map = false;
    std::string scan_channel = "LMS_SCAN", map_channel = "TERRAIN_MAP";
    app.add_flag("--scan-to-map", scan_to_map, "latency from each laser scan to the first map holding its points");
    app.add_option("--scan-channel", scan_channel, "with --scan-to-map");
    app.add_option("--map-channel", map_channel, "with --scan-to-map");
    std::string latency_from, latency_to;
    auto* from_opt = app.add_option("--latency-from", latency_from,
                                    "input channel: the latency to --latency-to's messages of the same utime");
    app.add_option("--latency-to", latency_to, "output channel, with --latency-from")->needs(from_opt);
    from_opt->needs(app.get_option("--latency-to"));
    CLI11_PARSE(app, argc, argv);

    std::unique_ptr<ugv::bus::Bus> bus;
    try {
        bus = ugv::bus::open_log_replay(log);
    } catch (const ugv::bus::BusError& e) {
        std::fprintf(stderr, "ugv-logstat: %s\n", e.what());
        return 2;
    }
    if (scan_to_map) {
        ugv::logstat::ScanToMapLatency latency;
        ugv::bus::subscribe<ugv::laser_scan_t>(
            *bus, scan_channel, [&](const std::string&, const ugv::laser_scan_t& s, int64_t t) {
                const double span_us = last_beam_offset_s(s) * 1e6;
                latency.add_scan(t, ugv::logstat::shifted_utime(s.utime, span_us));
            });
        bus->subscribe(map_channel, [&](const std::string&, const uint8_t* d, std::size_t n, int64_t t) {
            int64_t utime = 0, seq = 0;
            if (ugv::logstat::read_header(d, n, utime, seq)) latency.add_map(t, utime);
        });
        while (bus->handle(0) == ugv::bus::HandleResult::handled) {
        }
        const auto& v = latency.latencies_us();
        if (v.empty()) {
            std::fprintf(stderr, "ugv-logstat: no scan on %s is covered by a map on %s\n", scan_channel.c_str(),
                         map_channel.c_str());
            return 1;
        }
        std::printf("%s -> %s latency over %zu scans: p50 %.1f ms, p99 %.1f ms, max %.1f ms (%zu scans not in a map)\n",
                    scan_channel.c_str(), map_channel.c_str(), v.size(), static_cast<double>(ugv::logstat::percentile(v, 50)) / 1e3,
                    static_cast<double>(ugv::logstat::percentile(v, 99)) / 1e3,
                    static_cast<double>(ugv::logstat::percentile(v, 100)) / 1e3, latency.pending());
        return 0;
    }
    if (!latency_from.empty()) {
        ugv::logstat::StampLatency latency;
        bus->subscribe(latency_from, [&](const std::string&, const uint8_t* d, std::size_t n, int64_t t) {
            int64_t utime = 0, seq = 0;
            if (ugv::logstat::read_header(d, n, utime, seq)) latency.add_input(t, utime);
        });
        bus->subscribe(latency_to, [&](const std::string&, const uint8_t* d, std::size_t n, int64_t t) {
            int64_t utime = 0, seq = 0;
            if (ugv::logstat::read_header(d, n, utime, seq)) latency.add_output(t, utime);
        });
        while (bus->handle(0) == ugv::bus::HandleResult::handled) {
        }
        const auto& v = latency.latencies_us();
        if (v.empty()) {
            std::fprintf(stderr, "ugv-logstat: no message on %s answers one on %s\n", latency_to.c_str(),
                         latency_from.c_str());
            return 1;
        }
        std::printf("%s -> %s added latency over %zu messages: p50 %.1f ms, p99 %.1f ms, max %.1f ms (%zu inputs "
                    "unanswered, %zu answers received before their input, timed as 0)\n",
                    latency_from.c_str(), latency_to.c_str(), v.size(),
                    static_cast<double>(ugv::logstat::percentile(v, 50)) / 1e3,
                    static_cast<double>(ugv::logstat::percentile(v, 99)) / 1e3,
                    static_cast<double>(ugv::logstat::percentile(v, 100)) / 1e3, latency.unanswered(), latency.early());
        return 0;
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
                        json_escaped(ch).c_str(), static_cast<long long>(s.count), s.rate_hz(),
                        static_cast<double>(s.max_interval_us) / 1e3, kb * 1024.0, static_cast<long long>(s.seq_gaps), static_cast<long long>(s.seq_backwards));
        else
            std::printf("%-24s %8lld %9.2f %10.1f %9.2f %6lld %12lld\n", ch.c_str(), static_cast<long long>(s.count), s.rate_hz(),
                        static_cast<double>(s.max_interval_us) / 1e3, kb, static_cast<long long>(s.seq_gaps),
                        static_cast<long long>(s.seq_backwards));
    }
    return 0;
}
