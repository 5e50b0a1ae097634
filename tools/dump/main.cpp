// ugv-dump: any ugv message as one JSON line, from a live bus or a log.
//   ugv-dump [--lcm-url URL | --log FILE] [--channel REGEX] [--count N] [--timeout SECONDS]
// Exit status: 0 when done (log read, N messages printed, or interrupted with N = 0),
// 1 when the timeout passes with fewer than N messages, 2 for bad arguments or inputs.
#include <cstdio>
#include <optional>
#include <regex>

#include <CLI/CLI.hpp>

#include "ugv/bus/bus.hpp"
#include "ugv/dump/dump_filter.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/reflect.hpp"
#include "ugv/runtime/stop_signals.hpp"

int main(int argc, char** argv)
{
    std::string url, log, channel = ".*";
    int64_t count = 0;
    double timeout_s = 0;
    bool show_unknown = false;
    CLI::App app{"ugv-dump: print ugv LCM messages as JSON lines"};
    app.set_version_flag("--version", std::string("ugv-dump ") + UGV_VERSION);
    auto* url_opt = app.add_option("--lcm-url", url, "live LCM URL (default: LCM_DEFAULT_URL, else udpm ttl=0)");
    app.add_option("--log", log, "read this LCM log instead of the live bus")->check(CLI::ExistingFile)->excludes(url_opt);
    app.add_option("--channel", channel, "only channels matching this regex (whole name)");
    app.add_option("--count", count, "stop after N messages (0 = no limit)")->check(CLI::NonNegativeNumber);
    app.add_option("--timeout", timeout_s, "give up after SECONDS (exit 1 if fewer than --count)")->check(CLI::NonNegativeNumber);
    app.add_flag("--unknown", show_unknown, "also print messages of non-ugv types (as their size)");
    CLI11_PARSE(app, argc, argv);

    std::optional<ugv::dump::DumpFilter> filter;
    try {
        filter.emplace(channel, count);
    } catch (const std::regex_error& e) {
        std::fprintf(stderr, "ugv-dump: --channel '%s' is not a valid regex: %s\n", channel.c_str(), e.what());
        return 2;
    }
    std::unique_ptr<ugv::bus::Bus> bus;
    try {
        bus = log.empty() ? ugv::bus::open_live(url.empty() ? ugv::bus::default_url() : url) : ugv::bus::open_log_replay(log);
    } catch (const ugv::bus::BusError& e) {
        std::fprintf(stderr, "ugv-dump: %s\n", e.what());
        return 2;
    }
    int64_t malformed = 0;
    bus->subscribe(".*", [&](const std::string& ch, const uint8_t* data, std::size_t size, int64_t recv_utime) {
        if (filter->done() || !filter->wants(ch)) return;
        std::string type, fields;
        switch (ugv::reflect::to_json(data, size, type, fields)) {
        case ugv::reflect::DecodeResult::ok:
            std::printf("%s\n", ugv::dump::json_line(ch, type, fields, recv_utime).c_str());
            break;
        case ugv::reflect::DecodeResult::unknown_type:
            if (!show_unknown) return;
            std::printf("%s\n", ugv::dump::json_line(ch, "unknown", "{\"size\":" + std::to_string(size) + "}", recv_utime).c_str());
            break;
        case ugv::reflect::DecodeResult::malformed:
            ++malformed;
            std::fprintf(stderr, "ugv-dump: %s: a %s that does not decode (%zu bytes), skipped\n", ch.c_str(), type.c_str(), size);
            return;
        }
        std::fflush(stdout);
        filter->printed();
    });

    ugv::runtime::install_stop_signals();
    const int64_t deadline = timeout_s > 0 ? ugv::io::monotonic_us() + static_cast<int64_t>(timeout_s * 1e6) : INT64_MAX;
    while (!filter->done() && !ugv::runtime::stop_requested() && ugv::io::monotonic_us() < deadline) {
        const auto r = bus->handle(50);
        if (r == ugv::bus::HandleResult::end || r == ugv::bus::HandleResult::error) break;
    }
    if (count > 0 && filter->printed_count() < count) {
        std::fprintf(stderr, "ugv-dump: %lld of %lld messages%s\n", static_cast<long long>(filter->printed_count()),
                     static_cast<long long>(count), log.empty() ? " before the timeout" : " in the log");
        return 1;
    }
    return 0;
}
