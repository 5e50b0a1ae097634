// The LMS 2xx variants: the emulator acts as each (type string, status and configuration
// blocks, factory units and measuring mode), and the session's handshake against each ends
// streaming at the configured units in the 8/80 m mode, the configuration block written back
// at the length the device sent. Simulated time (emulated_line.hpp): no real time spent.
#include <catch2/catch.hpp>

#include <cmath>

#include "emulated_line.hpp"
#include "lms_variants.hpp"
#include "ugv/sick_lms2xx/model.hpp"
#include "ugv/sick_lms2xx/replies.hpp"
#include "ugv/sick_lms2xx/requests.hpp"
#include "ugv/sick_lms2xx/session.hpp"

using namespace ugv::sick_lms2xx;
using ugv::test::EmulatedLine;
namespace sim = ugv::sim::lms;

namespace {

// Sends one request to a bare device and hands the reply telegram (after the ACK byte) to
// check while the decoder still holds its bytes (a Telegram's data is a view into them).
template <typename Check>
void ask(sim::LmsDevice& dev, const std::vector<uint8_t>& request, Check check)
{
    std::vector<uint8_t> out;
    dev.receive(request.data(), request.size(), 9600, 1'000'000, out);
    REQUIRE(out.size() > 1);
    CHECK(out[0] == kAck);
    Decoder d(kDeviceAddress);
    int telegrams = 0;
    d.feed(out.data() + 1, out.size() - 1, [&](const DecoderEvent& ev) {
        if (ev.kind != DecoderEvent::Kind::telegram) return;
        ++telegrams;
        check(ev.telegram);
    });
    CHECK(telegrams == 1);
}

}  // namespace

TEST_CASE("model_from_type: the five LMS 2xx models, nothing else", "[sick_lms2xx][variants]")
{
    CHECK(model_from_type("LMS200;30106") == 200);
    CHECK(model_from_type("LMS211;30206") == 211);
    CHECK(model_from_type("LMS220;30106") == 220);
    CHECK(model_from_type("LMS221;30206") == 221);
    CHECK(model_from_type("LMS291;S05") == 291);
    CHECK(model_from_type("LMS291") == 291);
    CHECK_FALSE(model_from_type("LMS2910"));
    CHECK_FALSE(model_from_type("LMS400;1"));
    CHECK_FALSE(model_from_type("LMS1xx"));
    CHECK_FALSE(model_from_type("lms200"));
    CHECK_FALSE(model_from_type(""));
}

TEST_CASE("emulator variants: what each answers to 3A, 31 and 74 at power-on", "[lms][emulator][variants]")
{
    CHECK(sim::variants().size() == 5);
    CHECK_THROWS_WITH(sim::find_variant("LMS999"),
                      "--variant: 'LMS999' is not one of LMS200, LMS211, LMS220, LMS221, LMS291");
    CHECK(sim::find_variant("291").name == "LMS291");
    for (const auto& v : sim::variants()) {
        INFO(v.name);
        sim::DeviceOptions o;
        o.variant = v;
        sim::LmsDevice dev(o);
        ask(dev, request_type(), [&](const Telegram& t) { CHECK(decode_type_reply(t) == v.type_string); });
        CHECK(model_from_type(v.type_string) == std::stoi(v.name.substr(3)));
        ask(dev, request_status(), [&](const Telegram& t) {
            const auto st = decode_status_reply(t);
            REQUIRE(st);
            CHECK(st->version == v.software_version.substr(0, 7));
            CHECK(st->block.size() == v.status_bytes);
            CHECK(st->block[7] == 0x25);  // request mode: not streaming
        });
        ask(dev, request_read_config(), [&](const Telegram& t) {
            const auto cfg = decode_config_reply(t);
            REQUIRE(cfg);
            // The fact sheet: 32-42 bytes by firmware; units and measuring mode as from the factory.
            CHECK(cfg->block.size() == v.config_bytes);
            CHECK(cfg->block.size() >= 32);
            CHECK(cfg->block.size() <= 42);
            CHECK(cfg->units() == v.factory_units);
            CHECK(cfg->measuring_mode() == v.factory_measuring_mode);
        });
    }
}

TEST_CASE("the session's handshake against every variant, mm and cm", "[sick_lms2xx][session][variants]")
{
    for (const auto& v : sim::variants()) {
        for (const Units units : {Units::mm, Units::cm}) {
            INFO(v.name << (units == Units::mm ? " mm" : " cm"));
            sim::DeviceOptions o;
            o.variant = v;
            o.scene = sim::flat_floor_scene(1.0, 10.0 * 3.14159265358979323846 / 180.0);
            EmulatedLine line(o);
            std::vector<StampedScan> scans;
            SessionCallbacks cb;
            cb.on_scan = [&](const StampedScan& s) { scans.push_back(s); };
            cb.monotonic_us = [&] { return line.now_us; };
            cb.sleep_us = [&](int64_t us) { line.now_us += us; };
            SessionConfig cfg;
            cfg.units = units;
            Session s(line, cfg, cb);
            REQUIRE(s.initialise());
            CHECK(s.device_type() == v.type_string);
            CHECK(s.device_model() == std::stoi(v.name.substr(3)));
            CHECK(s.software_version() == "V" + v.software_version.substr(1, 5));
            CHECK(s.config_block_bytes() == v.config_bytes);
            // The device as the handshake left it: streaming 180/0.5 at 500000 baud, in the
            // 8/80 m mode and the asked units, its configuration block as long as before.
            const auto& dev = line.device();
            CHECK(dev.streaming());
            CHECK(dev.baud() == 500000);
            CHECK(dev.units() == units);
            CHECK(dev.config_block().size() == v.config_bytes);
            CHECK(dev.config_block()[DeviceConfig::measuring_mode_at] == kMeasuringMode8m80m);
            const int64_t end = line.now_us + 500'000;
            while (line.now_us < end) REQUIRE(s.pump(50) == Session::PumpResult::ok);
            REQUIRE(scans.size() >= 15);
            const StampedScan& sc = scans.back();
            REQUIRE(sc.scan.ranges_m.size() == 361);
            CHECK(sc.range_max_m == Approx(units == Units::mm ? 8.182 : 81.82));
            // Straight ahead: the floor at 1 m / sin(10 deg), to the unit's step.
            CHECK(sc.scan.ranges_m[180] == Approx(1.0 / std::sin(10.0 * 3.14159265358979323846 / 180.0))
                                               .margin(units == Units::mm ? 0.0011 : 0.011));
            CHECK(s.stats().naks == 0);
        }
    }
}

TEST_CASE("a configuration write with a measuring mode the variant lacks is refused", "[lms][emulator][variants]")
{
    sim::Variant v = sim::find_variant("LMS200");
    v.measuring_modes = {0x06};  // a unit that only does the 32 m mode
    sim::DeviceOptions o;
    o.variant = v;
    EmulatedLine line(o);
    SessionCallbacks cb;
    cb.monotonic_us = [&] { return line.now_us; };
    cb.sleep_us = [&](int64_t us) { line.now_us += us; };
    Session s(line, SessionConfig{}, cb);
    CHECK_FALSE(s.initialise());
    CHECK(s.last_error() == "write configuration: refused");
    CHECK_FALSE(line.device().streaming());
}
