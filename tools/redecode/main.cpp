// ugv-redecode LOG: runs every RAW_* channel of an LCM log (recorded with publish_raw on)
// through the codecs the daemons use and compares what comes out with what the daemons
// published in the same log. One JSON line per raw channel, then a summary line; exit 0 when
// everything matched, 1 on any mismatch (or no raw channel), 2 on bad arguments or an
// unreadable log. docs/runtime.md, "Tools".
#include <CLI/CLI.hpp>

#include <cstdio>
#include <stdexcept>

#include "ugv/redecode/redecode.hpp"

int main(int argc, char** argv)
{
    CLI::App app{"ugv-redecode: decode a log's RAW_* channels again and compare with what was published"};
    app.set_version_flag("--version", std::string("ugv-redecode ") + UGV_VERSION);
    std::string log;
    ugv::redecode::Options o;
    app.add_option("LOG", log, "LCM log recorded with publish_raw on")->required()->check(CLI::ExistingFile);
    app.add_option("--gps-baud", o.gps_baud, "ugv-gps `baud` (default 9600)")->check(CLI::PositiveNumber);
    app.add_option("--gps-leap-seconds", o.gps_leap_seconds, "ugv-gps `leap_seconds` (default 18)")->check(CLI::Range(0, 60));
    app.add_option("--gps-output-latency-ms", o.gps_output_latency_ms, "ugv-gps `output_latency_ms` (default 0)")
        ->check(CLI::Range(0.0, 1000.0));
    app.add_option("--imu-command", o.imu_command, "ugv-imu `command` (default 0x31)")->check(CLI::Range(0, 255));
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    std::vector<ugv::redecode::ChannelResult> results;
    try {
        results = ugv::redecode::redecode_log(log, o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "ugv-redecode: %s: %s\n", log.c_str(), e.what());
        return 2;
    }
    int bad = 0;
    for (const auto& r : results) {
        std::printf("%s\n", ugv::redecode::to_json(r).c_str());
        if (!r.ok()) ++bad;
    }
    std::printf("{\"summary\":true,\"raw_channels\":%zu,\"mismatched\":%d,\"ok\":%s}\n", results.size(), bad,
                bad == 0 && !results.empty() ? "true" : "false");
    if (results.empty()) std::fprintf(stderr, "ugv-redecode: %s: no RAW_* channel (was publish_raw on?)\n", log.c_str());
    return bad == 0 && !results.empty() ? 0 : 1;
}
