// ugv-expect: assertions on live traffic, for bench scripts.
//   ugv-expect --channel LMS_SCAN --for 5 --rate 35:40 --max-gap 0 --where 'ranges.size() == 361'
// Listens for --for seconds (after the first message, or from the start with --from-start),
// prints one line with what it saw and exits 0 (PASS) or 1 (FAIL); 2 for bad arguments.
#include <cstdio>

#include <CLI/CLI.hpp>

#include "ugv/bus/bus.hpp"
#include "ugv/expect/expectation.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/reflect.hpp"
#include "ugv/runtime/stop_signals.hpp"

int main(int argc, char** argv)
{
    ugv::expect::Expectation e;
    std::string url, rate, where, log;
    double wait_s = 10.0;
    bool from_start = false, verbose = false;
    CLI::App app{"ugv-expect: check rate, sequence gaps and content of a channel"};
    app.set_version_flag("--version", std::string("ugv-expect ") + UGV_VERSION);
    app.add_option("--channel", e.channel, "channel name (exact)")->required();
    app.add_option("--for", e.window_s, "seconds to watch")->check(CLI::PositiveNumber);
    app.add_option("--rate", rate, "MIN:MAX in Hz (either side may be empty)");
    app.add_option("--max-gap", e.max_gap, "seq gaps allowed (and seq must never go back)");
    app.add_option("--min-count", e.min_count, "at least N messages");
    app.add_option("--where", where, "condition every message must meet, e.g. 'ranges.size() == 361 && seq >= 0'");
    app.add_option("--wait", wait_s, "seconds to wait for the first message (default 10)");
    app.add_flag("--from-start", from_start, "start the window at once, not at the first message");
    app.add_option("--lcm-url", url, "LCM URL (default LCM_DEFAULT_URL, else udpm ttl=0)");
    app.add_flag("-v,--verbose", verbose, "print the first message that fails --where");
    CLI11_PARSE(app, argc, argv);
    try {
        if (!rate.empty()) ugv::expect::parse_rate(rate, e);
        if (!where.empty()) e.where.emplace(where);
    } catch (const std::invalid_argument& ex) {
        std::fprintf(stderr, "ugv-expect: %s\n", ex.what());
        return 2;
    }
    std::unique_ptr<ugv::bus::Bus> bus;
    try {
        bus = ugv::bus::open_live(url.empty() ? ugv::bus::default_url() : url);
    } catch (const ugv::bus::BusError& ex) {
        std::fprintf(stderr, "ugv-expect: %s\n", ex.what());
        return 2;
    }
    ugv::expect::Observation o;
    int64_t window_end = 0;
    const int64_t window_us = static_cast<int64_t>(e.window_s * 1e6);
    if (from_start) window_end = ugv::io::monotonic_us() + window_us;
    bus->subscribe(e.channel, [&](const std::string&, const uint8_t* data, std::size_t size, int64_t recv) {
        const int64_t now = ugv::io::monotonic_us();
        if (window_end == 0) window_end = now + window_us;
        if (now > window_end) return;
        o.stats.add(data, size, recv);
        if (!e.where) return;
        std::string type, json;
        if (ugv::reflect::to_json(data, size, type, json) != ugv::reflect::DecodeResult::ok) {
            ++o.undecodable;
            return;
        }
        const auto fields = ugv::expect::parse_json(json);
        if (fields && e.where->matches(*fields)) {
            ++o.where_ok;
        } else {
            if (o.where_failed++ == 0) o.first_failing = json;
        }
    });
    ugv::runtime::install_stop_signals();
    const int64_t give_up = ugv::io::monotonic_us() + static_cast<int64_t>(wait_s * 1e6);
    while (!ugv::runtime::stop_requested()) {
        const int64_t now = ugv::io::monotonic_us();
        if (window_end != 0 && now > window_end) break;
        if (window_end == 0 && now > give_up) break;
        bus->handle(20);
    }
    const auto verdict = ugv::expect::judge(e, o);
    std::printf("%s%s\n", verdict.line.c_str(), o.stats.count == 0 ? " (nothing arrived)" : "");
    if (verbose && !o.first_failing.empty()) std::printf("first failing message: %s\n", o.first_failing.c_str());
    return verdict.pass ? 0 : 1;
}
