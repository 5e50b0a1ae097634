// ugv-redecode LOG on a log recorded as a vehicle records one (lcm-logger, the daemons with
// publish_raw on, on their emulators; a few seconds): every RAW_* channel decodes again to
// exactly what was published. Then on a copy of that log with one GPS fix's latitude changed
// and one LMS scan left out: both are found and the exit status says so.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include <ugv/gps_fix_t.hpp>
#include <ugv/imu_t.hpp>
#include <ugv/laser_scan_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;
using ugv::test::bin;
using ugv::test::Process;

namespace {

constexpr int kPort = 7915;

// A number field of the JSON line about channel (an output of ugv-redecode), -1 when absent.
int64_t field(const std::string& output, const std::string& channel, const std::string& name)
{
    std::istringstream in(output);
    std::string line;
    const std::string tag = "{\"channel\":\"" + channel + "\"";
    while (std::getline(in, line)) {
        const auto at = line.find(tag);
        if (at == std::string::npos) continue;
        const std::string rest = line.substr(at, line.find('}', at) - at);
        std::smatch m;
        if (std::regex_search(rest, m, std::regex("\"" + name + "\":(-?[0-9]+)"))) return std::stoll(m[1]);
    }
    return -1;
}

}  // namespace

TEST_CASE("ugv-redecode: a log's raw bytes decode again to what the daemons published")
{
    test::TempDir dir;
    const std::string url = test::lcm_url(kPort), log = dir / "ugv.lcm";
    // What the daemons publish, seen live: the log is long enough once each has a few.
    auto bus = bus::open_live(url);
    std::map<std::string, int> seen;
    bus::subscribe<laser_scan_t>(*bus, "LMS_SCAN", [&](const std::string& c, const laser_scan_t&, int64_t) { ++seen[c]; });
    bus::subscribe<gps_fix_t>(*bus, "GPS_FIX", [&](const std::string& c, const gps_fix_t&, int64_t) { ++seen[c]; });
    bus::subscribe<imu_t>(*bus, "IMU", [&](const std::string& c, const imu_t&, int64_t) { ++seen[c]; });

    Process logger({"/usr/bin/lcm-logger", "--lcm-url=" + url, "-f", log}, dir / "logger.out", dir / "logger.err",
                   {"LD_PRELOAD=" UGV_LCM_QUEUE_LIB});
    REQUIRE(test::wait_until([&] { return std::filesystem::exists(log); }, 10));
    Process sim_lms({bin("ugv-sim"), "lms", "--pty", dir / "lms", "--height", "1.0", "--pitch-deg", "10"}, dir / "sl.out",
                    dir / "sl.err");
    Process sim_gps({bin("ugv-sim"), "gps", "--pty", dir / "gps"}, dir / "sg.out", dir / "sg.err");
    Process sim_imu({bin("ugv-sim"), "imu", "--pty", dir / "imu"}, dir / "si.out", dir / "si.err");
    REQUIRE(test::wait_until([&] {
        return std::filesystem::exists(dir / "lms") && std::filesystem::exists(dir / "gps") &&
               std::filesystem::exists(dir / "imu");
    }, 10));
    test::write_file(dir / "lms.toml", "device = \"" + dir / "lms" + "\"\nbaud = 500000\npublish_raw = true\n");
    test::write_file(dir / "gps.toml", "device = \"" + dir / "gps" + "\"\npublish_raw = true\n");
    test::write_file(dir / "imu.toml", "device = \"" + dir / "imu" + "\"\npublish_raw = true\n");
    std::map<std::string, std::unique_ptr<Process>> daemons;
    for (const std::string d : {"lms", "gps", "imu"})
        daemons[d] = std::make_unique<Process>(
            std::vector<std::string>{bin("ugv-" + d), "--config", dir / (d + ".toml"), "--lcm-url", url},
            dir / (d + ".out"), dir / (d + ".err"));
    const bool enough = [&] {
        const int64_t end = io::monotonic_us() + 30'000'000;
        while (io::monotonic_us() < end && !(seen["LMS_SCAN"] >= 60 && seen["GPS_FIX"] >= 8 && seen["IMU"] >= 100))
            bus->handle(20);
        return seen["LMS_SCAN"] >= 60 && seen["GPS_FIX"] >= 8 && seen["IMU"] >= 100;
    }();
    for (auto& [name, p] : daemons) {
        p->signal(SIGTERM);
        CHECK(p->wait_exit(5.0) == 0);
    }
    INFO("ugv-lms: " << daemons["lms"]->err() << "ugv-gps: " << daemons["gps"]->err() << "ugv-imu: " << daemons["imu"]->err());
    REQUIRE(enough);
    // The last messages reach the logger before it stops.
    bus->handle(300);
    logger.signal(SIGINT);
    REQUIRE(logger.wait_exit(5.0) == 0);

    Process run({bin("ugv-redecode"), log}, dir / "r1.out", dir / "r1.err");
    const int status = run.wait_exit(60);
    const std::string out = run.out();
    INFO(out << run.err());
    CHECK(status == 0);
    for (const char* ch : {"LMS_SCAN", "GPS_FIX", "GPS_VEL", "IMU"}) {
        INFO(ch);
        CHECK(field(out, ch, "decoded") > 0);
        CHECK(field(out, ch, "matched") == field(out, ch, "published"));
        CHECK(field(out, ch, "matched") == field(out, ch, "decoded"));
    }
    CHECK(field(out, "LMS_SCAN", "matched") >= 60);
    CHECK(out.find("\"summary\":true,\"raw_channels\":3,\"mismatched\":0,\"ok\":true") != std::string::npos);

    // The same log with the 3rd fix moved 1e-6 deg north and the 5th scan left out.
    const std::string tampered = dir / "tampered.lcm";
    {
        auto in = bus::open_log_replay(log);
        bus::Bus* src = in.get();
        auto outlog = bus::open_log_writer(tampered, [src] { return src->now_utime(); });
        int fixes = 0, scans = 0;
        in->subscribe(".*", [&](const std::string& ch, const uint8_t* data, std::size_t n, int64_t) {
            if (ch == "LMS_SCAN" && ++scans == 5) return;
            if (ch == "GPS_FIX" && ++fixes == 3) {
                gps_fix_t f{};
                REQUIRE(f.decode(data, 0, static_cast<int>(n)) == static_cast<int>(n));
                f.latitude += 1e-6;
                bus::publish(*outlog, ch, f);
                return;
            }
            outlog->publish(ch, data, n);
        });
        while (in->handle(0) == bus::HandleResult::handled) {
        }
    }
    Process again({bin("ugv-redecode"), tampered}, dir / "r2.out", dir / "r2.err");
    CHECK(again.wait_exit(60) == 1);
    const std::string out2 = again.out();
    INFO(out2);
    CHECK(field(out2, "GPS_FIX", "field_mismatches") == 1);
    CHECK(field(out2, "LMS_SCAN", "decoded_only") == 1);
    CHECK(field(out2, "LMS_SCAN", "published_only") == 0);
    CHECK(field(out2, "IMU", "matched") == field(out, "IMU", "matched"));
    CHECK(out2.find("\"mismatched\":2") != std::string::npos);
}
