// ugv-gps against `ugv-sim gps` on a pseudo-terminal, real LCM: both modes, both protocols,
// a receiver unplugged and plugged back, and a bad config key.
#include <catch2/catch.hpp>

#include <mutex>
#include <string>
#include <vector>

#include "gps_rig.hpp"

using ugv::test::Process;
using ugv::test::TempDir;
using ugv::test::gps::check_position;
using ugv::test::gps::kLat;
using ugv::test::gps::kLon;
using ugv::test::gps::Listener;
using ugv::test::gps::Rig;

TEST_CASE("ugv-gps configure mode, NovAtel binary: fix types follow the script, times are GPS time")
{
    Listener l(7750);
    Rig rig;
    rig.start_sim({"--protocol", "novatel", "--fix-script", "SINGLE@0,PSRDIFF@1.5,NARROW_INT@3"});
    rig.start_daemon("mode = \"configure\"\nprotocol = \"novatel\"\nlogs = [\"BESTPOSB 0.1\", \"BESTVELB 0.2\"]\n", 7750);
    const bool rtk = l.wait([&] {
        std::lock_guard<std::mutex> g(l.t.m);
        return !l.t.fixes.empty() && l.t.fixes.back().fix_quality == ugv::gps_fix_t::QUALITY_RTK_FIXED;
    }, 20.0);
    INFO(rig.logs());
    REQUIRE(rtk);
    REQUIRE(l.wait([&] { return l.t.counter("frames_binary") > 0; }, 5.0));
    CHECK(l.t.counter("crc_errors") == 0);
    CHECK(l.t.counter("configure_failures") == 0);
    CHECK(l.t.counter("commands_sent") == 3);
    std::lock_guard<std::mutex> g(l.t.m);
    bool saw_single = false, saw_dgps = false;
    for (std::size_t i = 0; i < l.t.fixes.size(); ++i) {
        const auto& f = l.t.fixes[i];
        saw_single |= f.fix_quality == ugv::gps_fix_t::QUALITY_SINGLE;
        saw_dgps |= f.fix_quality == ugv::gps_fix_t::QUALITY_DGPS;
        check_position(f);
        CHECK(f.source == ugv::gps_fix_t::SOURCE_NOVATEL_BINARY);
        CHECK(f.gps_week > 2000);
        // ONTIME 0.1: measurement times on 100 ms boundaries of GPS time.
        CHECK(f.gps_ms % 100 == 0);
        CHECK(f.seq == static_cast<int64_t>(i));
        // Measured before it was received, and not long before (a loaded machine: 2 s).
        CHECK(f.utime <= l.t.fix_recv[i]);
        CHECK(l.t.fix_recv[i] - f.utime < 2'000'000);
    }
    CHECK(saw_single);
    CHECK(saw_dgps);
    CHECK_FALSE(l.t.vels.empty());
}

TEST_CASE("ugv-gps passive mode, NovAtel binary: sends nothing, reads a preconfigured receiver")
{
    Listener l(7751);
    Rig rig;
    rig.start_sim({"--protocol", "novatel", "--preconfigured", "--rate-hz", "10", "--fix-script", "PSRDIFF@0"});
    rig.start_daemon("mode = \"passive\"\n", 7751);
    INFO(rig.logs());
    REQUIRE(l.wait([&] { return l.t.nfix() >= 10; }, 20.0));
    REQUIRE(l.wait([&] { return l.t.counter("fixes_published") >= 10; }, 5.0));
    CHECK(l.t.counter("commands_sent") == 0);
    std::lock_guard<std::mutex> g(l.t.m);
    check_position(l.t.fixes.back());
    CHECK(l.t.fixes.back().fix_quality == ugv::gps_fix_t::QUALITY_DGPS);
    CHECK(l.t.fixes.back().sigma_latitude == Approx(0.4));
}

TEST_CASE("ugv-gps configure mode, NMEA: LOG GPGGA/GPRMC/GPGST, sigmas from GST")
{
    Listener l(7752);
    Rig rig;
    rig.start_sim({"--protocol", "nmea", "--fix-script", "NARROW_INT@0"});
    rig.start_daemon("mode = \"configure\"\nprotocol = \"nmea\"\nperiod_s = 0.1\n", 7752);
    INFO(rig.logs());
    REQUIRE(l.wait([&] { return l.t.nfix() >= 10; }, 20.0));
    REQUIRE(l.wait([&] { return l.t.counter("frames_nmea") > 0; }, 5.0));
    CHECK(l.t.counter("commands_sent") == 4);
    std::lock_guard<std::mutex> g(l.t.m);
    const auto& f = l.t.fixes.back();
    CHECK(f.source == ugv::gps_fix_t::SOURCE_NMEA);
    CHECK(f.fix_quality == ugv::gps_fix_t::QUALITY_RTK_FIXED);
    CHECK(f.position_type == 4);  // the GGA quality
    CHECK_THAT(f.latitude, Catch::Matchers::WithinAbs(kLat, 1e-6));  // NMEA prints 7 decimals of minutes
    CHECK_THAT(f.longitude, Catch::Matchers::WithinAbs(kLon, 1e-6));
    CHECK(f.sigma_latitude == Approx(0.02));
    CHECK(f.sigma_height == Approx(0.03));
    CHECK(f.gps_ms % 100 == 0);
    CHECK_FALSE(l.t.vels.empty());
}

TEST_CASE("ugv-gps passive mode, NMEA (auto protocol)")
{
    Listener l(7753);
    Rig rig;
    rig.start_sim({"--protocol", "nmea", "--preconfigured", "--rate-hz", "10", "--fix-script", "WAAS@0"});
    rig.start_daemon("mode = \"passive\"\nprotocol = \"auto\"\n", 7753);
    INFO(rig.logs());
    REQUIRE(l.wait([&] { return l.t.nfix() >= 10; }, 20.0));
    std::lock_guard<std::mutex> g(l.t.m);
    CHECK(l.t.fixes.back().source == ugv::gps_fix_t::SOURCE_NMEA);
    CHECK(l.t.fixes.back().fix_quality == ugv::gps_fix_t::QUALITY_SBAS);
}

TEST_CASE("ugv-gps: receiver unplugged and back: DEGRADED, reconnect, reconfigure, fixes again")
{
    Listener l(7754);
    Rig rig;
    rig.start_sim({"--protocol", "novatel", "--unplug-at", "3", "--unplug-for", "1.5"});
    rig.start_daemon("mode = \"configure\"\nlogs = [\"BESTPOSB 0.1\"]\n", 7754);
    INFO(rig.logs());
    REQUIRE(l.wait([&] { return l.t.nfix() >= 5; }, 20.0));
    REQUIRE(l.wait([&] { return l.t.counter("reconnects") >= 1; }, 20.0));
    CHECK(l.wait([&] { return l.t.saw_state(ugv::daemon_status_t::STATE_DEGRADED); }, 5.0));
    const std::size_t before = l.t.nfix();
    REQUIRE(l.wait([&] { return l.t.nfix() >= before + 10; }, 20.0));
    CHECK(l.wait([&] {
        std::lock_guard<std::mutex> g(l.t.m);
        return !l.t.status.empty() && l.t.status.back().state == ugv::daemon_status_t::STATE_RUNNING;
    }, 5.0));
    // Reconfigured after the reconnect: UNLOGALL + LOG twice.
    CHECK(l.t.counter("commands_sent") >= 4);
    std::lock_guard<std::mutex> g(l.t.m);
    for (std::size_t i = 1; i < l.t.fixes.size(); ++i) {
        CHECK(l.t.fixes[i].seq == l.t.fixes[i - 1].seq + 1);
        CHECK(l.t.fixes[i].utime > l.t.fixes[i - 1].utime);
    }
}

TEST_CASE("ugv-gps: silence -> DEGRADED and a reconfigure; garbage is skipped")
{
    Listener l(7755);
    Rig rig;
    rig.start_sim({"--protocol", "novatel", "--silence-at", "2.5", "--silence-for", "2", "--garbage-period", "0.5"});
    rig.start_daemon("mode = \"configure\"\nlogs = [\"BESTPOSB 0.1\"]\nsilence_timeout_s = 0.8\n", 7755);
    INFO(rig.logs());
    REQUIRE(l.wait([&] { return l.t.counter("silences") >= 1; }, 20.0));
    const std::size_t before = l.t.nfix();
    REQUIRE(l.wait([&] { return l.t.nfix() >= before + 10; }, 20.0));
    CHECK(l.t.counter("resyncs") > 0);
    CHECK(l.t.saw_state(ugv::daemon_status_t::STATE_DEGRADED));
}

TEST_CASE("ugv-gps: a bad config key exits 2 with FILE: KEY: why")
{
    TempDir dir;
    ugv::test::write_file(dir / "gps.toml", "mode = \"configure\"\nlogs = [\"BESTPOSB fast\"]\n");
    const int rc = ugv::test::run({ugv::test::bin("ugv-gps"), "--config", dir / "gps.toml", "--lcm-url",
                                   ugv::test::lcm_url(7756)},
                                  dir / "out", dir / "err", 20.0);
    CHECK(rc == 2);
    const std::string err = ugv::test::read_file(dir / "err");
    CHECK(err.find("gps.toml") != std::string::npos);
    CHECK(err.find("logs") != std::string::npos);
    CHECK(err.find("period") != std::string::npos);
}
