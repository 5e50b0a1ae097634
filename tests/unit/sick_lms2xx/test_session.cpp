// The device session against the emulator core in simulated time: the full handshake, probing
// a device left at any rate, time stamps, recovery from silence and unplugging, refusals, and
// shutdown.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "emulated_line.hpp"
#include "ugv/sick_lms2xx/requests.hpp"
#include "ugv/sick_lms2xx/session.hpp"
#include "ugv/sick_lms2xx/timing.hpp"

using namespace ugv::sick_lms2xx;
using ugv::test::EmulatedLine;
namespace sim = ugv::sim::lms;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kHeight = 1.0;
constexpr double kPitch = 10.0 * kPi / 180.0;

sim::DeviceOptions device_options()
{
    sim::DeviceOptions o;
    o.scene = sim::flat_floor_scene(kHeight, kPitch);
    return o;
}

struct Harness
{
    EmulatedLine line;
    std::vector<StampedScan> scans;
    std::vector<SessionState> states;
    int64_t stop_at_us = INT64_MAX;
    int reopen_calls = 0;
    int reopen_succeeds_after = 3;
    SessionCallbacks callbacks()
    {
        SessionCallbacks cb;
        cb.on_scan = [this](const StampedScan& s) { scans.push_back(s); };
        cb.on_state = [this](SessionState s, const std::string&) { states.push_back(s); };
        cb.monotonic_us = [this] { return line.now_us; };
        cb.sleep_us = [this](int64_t us) { line.now_us += us; };
        cb.stop_requested = [this] { return line.now_us >= stop_at_us; };
        cb.reopen = [this] {
            if (++reopen_calls < reopen_succeeds_after) return false;
            line.replug();
            return true;
        };
        return cb;
    }
    explicit Harness(sim::DeviceOptions o = device_options()) : line(std::move(o)) {}
    // Pumps for seconds of simulated time.
    void stream_for(Session& s, double seconds)
    {
        const int64_t end = line.now_us + static_cast<int64_t>(seconds * 1e6);
        while (line.now_us < end) REQUIRE(s.pump(50) == Session::PumpResult::ok);
    }
};

}  // namespace

TEST_CASE("full handshake from 9600 to 500000 and 37.5 Hz scans with exact stamps", "[sick_lms2xx][session]")
{
    Harness h;
    SessionConfig cfg;  // 500000, 180 / 0.5, mm
    Session s(h.line, cfg, h.callbacks());
    REQUIRE(s.initialise());
    CHECK(s.device_baud() == 500000);
    CHECK(s.device_type() == "LMS200;30106");
    CHECK(h.line.bauds_set == std::vector<int>{9600, 500000});
    CHECK(h.line.device().baud() == 500000);
    CHECK(h.line.device().streaming());
    CHECK(h.line.device().angle_deg() == 180);
    CHECK(h.line.device().resolution_cdeg() == 50);
    CHECK(h.line.device().units() == Units::mm);
    CHECK_FALSE(h.line.device().installation_mode());  // streaming leaves installation mode
    CHECK(s.state() == SessionState::streaming);

    h.stream_for(s, 2.0);
    // 2 s at 26.67 ms: 75 scans, give or take the one in flight at either end.
    CHECK(h.scans.size() >= 74);
    CHECK(h.scans.size() <= 76);
    CHECK(s.stats().scans == static_cast<int64_t>(h.scans.size()));
    CHECK(s.stats().crc_errors == 0);
    CHECK(s.stats().naks == 0);
    const StampedScan& sc = h.scans.back();
    REQUIRE(sc.scan.ranges_m.size() == 361);
    // Beam 180 looks straight ahead: the floor at height / sin(pitch).
    CHECK(sc.scan.ranges_m[180] == Approx(kHeight / std::sin(kPitch)).margin(0.0011));
    // Beam 0 looks right along the floor: no echo within 8 m.
    CHECK(std::isnan(sc.scan.ranges_m[0]));
    CHECK(sc.scan.flags[0] == static_cast<int8_t>(BeamFlag::overflow));
    CHECK(sc.angle_min_rad == Approx(-kPi / 2));
    CHECK(sc.angle_increment_rad == Approx(0.5 * kPi / 180));
    CHECK(sc.scan_period_s == Approx(2.0 / 75.0));
    CHECK(sc.range_max_m == Approx(8.182));
    CHECK(sc.scan.scan_index == -1);
    // 732 bytes at 500000 baud = 14640 us on the wire; the scan started one mirror turn plus
    // one crossing of the 180 deg field (20000 us) before its last beam.
    CHECK(sc.first_beam_utime == sc.arrival_utime - 14640 - 20000);
    CHECK(sc.time_increment_s == Approx(0.5 / 360.0 / 75.0));
    CHECK(sc.sweep_period_s == Approx(1.0 / 75.0));
    CHECK(to_string(sc.sweep_order) == "01");
    // Consecutive scans one period apart.
    const int64_t dt = h.scans.back().first_beam_utime - h.scans[h.scans.size() - 2].first_beam_utime;
    CHECK(std::abs(dt - 26667) <= 1);
}

TEST_CASE("a device left streaming at any rate is found by probing", "[sick_lms2xx][session]")
{
    for (const int left_at : {9600, 19200, 38400, 500000}) {
        INFO("left at " << left_at);
        auto o = device_options();
        o.initial_baud = left_at;
        o.initially_streaming = true;
        Harness h(o);
        Session s(h.line, SessionConfig{}, h.callbacks());
        REQUIRE(s.initialise());
        CHECK(h.line.device().baud() == 500000);
        std::vector<int> expected;
        for (const int b : kSupportedBauds) {
            expected.push_back(b);
            if (b == left_at) break;
        }
        if (left_at != 500000) expected.push_back(500000);
        CHECK(h.line.bauds_set == expected);
        h.stream_for(s, 0.5);
        CHECK(h.scans.size() >= 17);
    }
}

TEST_CASE("38400 baud at 0.5 deg: the line limits the rate to about 5 Hz", "[sick_lms2xx][session]")
{
    Harness h;
    SessionConfig cfg;
    cfg.baud = 38400;
    Session s(h.line, cfg, h.callbacks());
    REQUIRE(s.initialise());
    h.stream_for(s, 3.0);
    // One scan per 8 periods (190.6 ms on the wire): 213 ms apart, 14 in 3 s.
    CHECK(h.scans.size() >= 13);
    CHECK(h.scans.size() <= 15);
    CHECK(h.scans.back().first_beam_utime == h.scans.back().arrival_utime - 190625 - 20000);
}

TEST_CASE("cm units, 100 deg / 0.25 deg and the real-time scan index", "[sick_lms2xx][session]")
{
    Harness h;
    SessionConfig cfg;
    cfg.angle_deg = 100;
    cfg.resolution_cdeg = 25;
    cfg.units = Units::cm;
    cfg.scan_index = true;
    Session s(h.line, cfg, h.callbacks());
    REQUIRE(s.initialise());
    CHECK(h.line.device().units() == Units::cm);
    CHECK((h.line.device().config_block()[4] & kAvailabilityScanIndex) != 0);
    h.stream_for(s, 1.0);
    REQUIRE(h.scans.size() >= 17);  // 53.3 ms per scan
    const StampedScan& sc = h.scans.back();
    REQUIRE(sc.scan.ranges_m.size() == 401);
    CHECK(sc.scan.units == Units::cm);
    CHECK(sc.range_max_m == Approx(81.82));
    CHECK(sc.angle_min_rad == Approx(-50.0 * kPi / 180));
    CHECK(sc.scan_period_s == Approx(4.0 / 75.0));
    CHECK(sc.scan.ranges_m[200] == Approx(kHeight / std::sin(kPitch)).margin(0.011));
    // Beam 0 at -50 deg: the floor at height / (sin(pitch) cos 50deg), inside 80 m.
    CHECK(sc.scan.ranges_m[0] == Approx(kHeight / (std::sin(kPitch) * std::cos(50 * kPi / 180))).margin(0.011));
    const int32_t a = h.scans[h.scans.size() - 2].scan.scan_index;
    CHECK(sc.scan.scan_index == (a + 1) % 256);
}

TEST_CASE("a wrong password fails the initialisation with a reason", "[sick_lms2xx][session]")
{
    auto o = device_options();
    o.password = "OTHERPWD";
    Harness h(o);
    Session s(h.line, SessionConfig{}, h.callbacks());
    CHECK_FALSE(s.initialise());
    CHECK(s.last_error() == "installation mode: wrong password");
    CHECK_FALSE(h.line.device().streaming());
}

TEST_CASE("no device: every rate probed, then a clear error", "[sick_lms2xx][session]")
{
    auto o = device_options();
    o.initial_baud = 115200;  // a rate the host never tries: nothing it sends is understood
    Harness none(o);
    Session s(none.line, SessionConfig{}, none.callbacks());
    CHECK_FALSE(s.initialise());
    CHECK(s.last_error() == "no LMS answered at 9600, 19200, 38400 or 500000 baud");
    CHECK(none.line.bauds_set == std::vector<int>{9600, 19200, 38400, 500000});
    CHECK(s.stats().timeouts == 8);  // two attempts per rate
}

TEST_CASE("silence for several scan periods: re-initialised without leaving run()", "[sick_lms2xx][session]")
{
    auto o = device_options();
    o.faults.silence_every_s = 4.0;
    o.faults.silence_for_s = 1.5;
    Harness h(o);
    // Silent in [2.5, 4) s and [6.5, 8) s: stop at 6 s, while the device answers again.
    h.stop_at_us = h.line.now_us + 6'000'000;
    Session s(h.line, SessionConfig{}, h.callbacks());
    s.run();
    CHECK(s.stats().reconnects >= 1);
    CHECK(s.stats().timeouts >= 1);
    // Scans before the first silence (2.5 s) and after it.
    REQUIRE(h.scans.size() > 100);
    const int64_t t_last = h.scans.back().arrival_utime - EmulatedLine::kEpochUs;
    CHECK(t_last > h.stop_at_us - 1'500'000);
    CHECK(s.state() == SessionState::stopped);
    CHECK_FALSE(h.line.device().streaming());  // stop_on_exit
}

TEST_CASE("a vanished device is reopened with back-off and re-initialised", "[sick_lms2xx][session]")
{
    Harness h;
    h.stop_at_us = h.line.now_us + 6'000'000;
    auto cb = h.callbacks();
    std::size_t unplug_after = 40;
    cb.on_scan = [&](const StampedScan& sc) {
        h.scans.push_back(sc);
        if (h.scans.size() == unplug_after) h.line.unplug();
    };
    Session s(h.line, SessionConfig{}, cb);
    s.run();
    CHECK(h.reopen_calls == 3);
    CHECK(s.stats().reconnects == 1);
    CHECK(h.scans.size() > unplug_after + 50);  // streaming again on the new device
    CHECK(h.line.device().baud() == 500000);
    CHECK_FALSE(h.line.device().streaming());
}

TEST_CASE("corrupted and garbage bytes: counted, never published", "[sick_lms2xx][session]")
{
    auto o = device_options();
    o.faults.bitflip_probability = 0.2;
    o.faults.garbage_probability = 0.2;
    o.seed = 7;
    Harness h(o);
    h.line.max_chunk = 100;  // telegrams split across reads
    h.stop_at_us = h.line.now_us + 5'000'000;
    Session s(h.line, SessionConfig{}, h.callbacks());
    s.run();
    CHECK(s.stats().crc_errors > 5);
    CHECK(s.stats().resyncs > 5);
    REQUIRE(h.scans.size() > 80);
    for (const StampedScan& sc : h.scans) {
        REQUIRE(sc.scan.ranges_m.size() == 361);
        REQUIRE(sc.scan.ranges_m[180] == Approx(kHeight / std::sin(kPitch)).margin(0.0011));
    }
}

TEST_CASE("stop_on_exit = false leaves the device streaming", "[sick_lms2xx][session]")
{
    Harness h;
    h.stop_at_us = h.line.now_us + 2'000'000;
    SessionConfig cfg;
    cfg.stop_on_exit = false;
    Session s(h.line, cfg, h.callbacks());
    s.run();
    CHECK(h.scans.size() > 30);
    CHECK(h.line.device().streaming());
}

TEST_CASE("invalid session configurations are refused", "[sick_lms2xx][session]")
{
    SessionConfig c;
    c.baud = 115200;
    CHECK_THROWS_WITH(validate(c), "baud: must be 9600, 19200, 38400 or 500000");
    c = SessionConfig{};
    c.resolution_cdeg = 25;
    CHECK_THROWS_WITH(validate(c), "resolution_deg: 0.25 deg needs angle_deg = 100");
    c = SessionConfig{};
    c.angle_deg = 90;
    CHECK_THROWS(validate(c));
    CHECK_NOTHROW(validate(SessionConfig{}));
}

namespace {
// A line on which every request is answered with NAK and nothing else.
class NakLine final : public ugv::io::ByteStream
{
public:
    int64_t now_us = 0;
    ugv::io::ReadResult read(uint8_t* buf, std::size_t cap, int timeout_ms) override
    {
        ugv::io::ReadResult r;
        if (pending_ == 0 || cap == 0) {
            now_us += int64_t{timeout_ms} * 1000;
            return r;
        }
        buf[0] = kNak;
        --pending_;
        r.status = ugv::io::ReadResult::Status::data;
        r.n = 1;
        r.utime = now_us;
        return r;
    }
    bool write(const uint8_t*, std::size_t) override
    {
        ++pending_;
        ++writes;
        return true;
    }
    bool set_baud(int b) override
    {
        baud_ = b;
        return true;
    }
    int baud() const override { return baud_; }
    void flush_input() override { pending_ = 0; }
    const std::string& last_error() const override { return error_; }
    int writes = 0;

private:
    int pending_ = 0;
    int baud_ = 9600;
    std::string error_;
};
}  // namespace

TEST_CASE("repeated NAKs: each request retried, then the initialisation fails", "[sick_lms2xx][session]")
{
    NakLine line;
    SessionCallbacks cb;
    cb.monotonic_us = [&] { return line.now_us; };
    cb.sleep_us = [&](int64_t us) { line.now_us += us; };
    Session s(line, SessionConfig{}, cb);
    CHECK_FALSE(s.initialise());
    CHECK(line.writes == 8);       // two probe attempts at each of four rates
    CHECK(s.stats().naks == 8);
    CHECK(s.stats().timeouts == 0);
    CHECK(s.stats().scans == 0);
}
