// The LMS emulator core, byte for byte: ACK + reply, NAK, refusals, the baud model, the
// streaming period and the scene.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

#include "fault_spec.hpp"
#include "lms_emulator.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"
#include "ugv/sick_lms2xx/replies.hpp"
#include "ugv/sick_lms2xx/requests.hpp"
#include "ugv/sick_lms2xx/scan.hpp"
#include "ugv/sick_lms2xx/timing.hpp"

using namespace ugv::sick_lms2xx;
namespace sim = ugv::sim::lms;
using Bytes = std::vector<uint8_t>;

namespace {

constexpr double kPi = 3.14159265358979323846;

struct Reply
{
    std::vector<DecoderEvent::Kind> kinds;
    std::vector<Bytes> raws;
    std::vector<uint8_t> commands;
    std::vector<Bytes> data;
};

Reply parse(const Bytes& out)
{
    Reply r;
    Decoder dec;
    dec.feed(out.data(), out.size(), [&](const DecoderEvent& ev) {
        r.kinds.push_back(ev.kind);
        if (ev.kind == DecoderEvent::Kind::telegram) {
            r.raws.emplace_back(ev.telegram.raw.begin(), ev.telegram.raw.end());
            r.commands.push_back(ev.telegram.command);
            r.data.emplace_back(ev.telegram.data.begin(), ev.telegram.data.end());
        }
    });
    return r;
}

Bytes ask(sim::LmsDevice& d, const Bytes& request, int host_baud = 9600, int64_t now = 1000)
{
    Bytes out;
    d.receive(request.data(), request.size(), host_baud, now, out);
    return out;
}

using K = DecoderEvent::Kind;

}  // namespace

TEST_CASE("emulator: ACK then the reply, byte exact", "[lms][emulator]")
{
    sim::LmsDevice d({});
    const Bytes out = ask(d, request_stop_streaming());
    Bytes expected = {kAck};
    const Bytes a0 = encode_reply(0xA0, Bytes{0x00}, 0x10);
    expected.insert(expected.end(), a0.begin(), a0.end());
    CHECK(out == expected);
    const Reply type = parse(ask(d, request_type()));
    REQUIRE(type.kinds == std::vector<K>{K::ack, K::telegram});
    CHECK(type.commands[0] == 0xBA);
    CHECK(std::string(type.data[0].begin(), type.data[0].end()) == "LMS200;30106");
}

TEST_CASE("emulator: NAK for a bad CRC and for an unknown command", "[lms][emulator]")
{
    sim::LmsDevice d({});
    Bytes bad = request_type();
    bad.back() ^= 0x01;
    CHECK(ask(d, bad) == Bytes{kNak});
    CHECK(ask(d, encode_request(0x55)) == Bytes{kNak});
    CHECK(d.stats().naks == 2);
}

TEST_CASE("emulator: the password", "[lms][emulator]")
{
    sim::LmsDevice d({});
    Reply r = parse(ask(d, request_installation_mode("WRONGPWD")));
    REQUIRE(r.commands.size() == 1);
    CHECK(r.data[0] == Bytes{kModeBadPassword});
    CHECK_FALSE(d.installation_mode());
    r = parse(ask(d, request_installation_mode()));
    CHECK(r.data[0] == Bytes{kModeOk});
    CHECK(d.installation_mode());
}

TEST_CASE("emulator: variant refused while streaming, accepted otherwise", "[lms][emulator]")
{
    sim::LmsDevice d({});
    ask(d, request_start_streaming());
    REQUIRE(d.streaming());
    Reply r = parse(ask(d, request_variant(100, 25)));
    REQUIRE(r.commands.size() == 1);
    CHECK(r.data[0] == Bytes{0x00, 0xB4, 0x00, 0x32, 0x00});  // refused, still 180 / 0.5
    CHECK(d.angle_deg() == 180);
    ask(d, request_stop_streaming());
    r = parse(ask(d, request_variant(100, 25)));
    CHECK(r.data[0] == Bytes{0x01, 0x64, 0x00, 0x19, 0x00});
    CHECK(d.angle_deg() == 100);
    CHECK(d.resolution_cdeg() == 25);
    // 180 deg at 0.25 deg does not exist.
    r = parse(ask(d, request_variant(180, 25)));
    CHECK(r.data[0][0] == 0x00);
}

TEST_CASE("emulator: configuration writes need installation mode", "[lms][emulator]")
{
    sim::LmsDevice d({});
    Reply r = parse(ask(d, request_read_config()));
    REQUIRE(r.commands == Bytes{0xF4});
    Bytes block = r.data[0];
    REQUIRE(block.size() == 32);
    CHECK(block[6] == kConfigUnitsCm);
    block[6] = kConfigUnitsMm;
    r = parse(ask(d, request_write_config(block)));
    CHECK(r.data[0][0] == 0x00);
    CHECK(d.units() == Units::cm);
    ask(d, request_installation_mode());
    r = parse(ask(d, request_write_config(block)));
    CHECK(r.data[0][0] == 0x01);
    CHECK(d.units() == Units::mm);
}

TEST_CASE("emulator: a host at another rate gets no answer and garbage", "[lms][emulator]")
{
    sim::LmsDevice d({});  // at 9600
    CHECK(ask(d, request_type(), 19200).empty());
    CHECK(d.stats().garbled_input == request_type().size());
    // Streaming at 9600, the host listening at 500000: garbage, never a telegram.
    ask(d, request_start_streaming());
    Bytes out;
    for (int64_t t = 0; t <= 2'000'000; t += 10'000) d.tick(t, 500000, out);
    CHECK(out.size() > 1000);
    const Reply r = parse(out);
    CHECK(r.raws.empty());
}

TEST_CASE("emulator: a baud switch answers at the old rate and listens at the new one", "[lms][emulator]")
{
    sim::LmsDevice d({});
    // The switch request followed, in the same chunk, by a type request still at 9600.
    Bytes chunk = request_baud(500000);
    const Bytes type = request_type();
    chunk.insert(chunk.end(), type.begin(), type.end());
    const Reply r = parse(ask(d, chunk, 9600));
    CHECK(r.commands == Bytes{0xA0});  // only the switch is answered
    CHECK(d.baud() == 500000);
    CHECK(ask(d, request_type(), 9600).empty());
    CHECK(parse(ask(d, request_type(), 500000)).commands == Bytes{0xBA});
    // Reset: back to 9600.
    CHECK(parse(ask(d, request_reset(), 500000)).commands == Bytes{0x91});
    CHECK(d.baud() == 9600);
}

TEST_CASE("emulator: scans at the real period with the flat floor", "[lms][emulator]")
{
    sim::DeviceOptions o;
    o.scene = sim::flat_floor_scene(0.8, 20.0 * kPi / 180.0);
    o.initial_baud = 500000;
    sim::LmsDevice d(o);
    ask(d, request_start_streaming(), 500000, 0);
    Bytes out;
    for (int64_t t = 0; t <= 1'000'000; t += 1000) d.tick(t, 500000, out);
    const Reply r = parse(out);
    // 26.667 ms per scan: 37 complete periods in 1 s.
    CHECK(r.raws.size() == 37);
    Scan s;
    Decoder dec;
    int decoded = 0;
    dec.feed(r.raws[0].data(), r.raws[0].size(), [&](const DecoderEvent& ev) {
        REQUIRE(decode_scan(ev.telegram, s) == ScanError::none);
        ++decoded;
    });
    REQUIRE(decoded == 1);
    REQUIRE(s.ranges_m.size() == 361);
    CHECK(s.units == Units::cm);
    CHECK(s.ranges_m[180] == Approx(0.8 / std::sin(20.0 * kPi / 180.0)).margin(0.006));
    // Beam 60 deg right of ahead: 0.8 / (sin 20 cos 60) = 4.68 m.
    CHECK(s.ranges_m[60] == Approx(0.8 / (std::sin(20.0 * kPi / 180.0) * 0.5)).margin(0.006));
}

TEST_CASE("emulator: the line rate limits scans at 38400", "[lms][emulator]")
{
    sim::DeviceOptions o;
    o.initial_baud = 38400;
    sim::LmsDevice d(o);
    ask(d, request_start_streaming(), 38400, 0);
    Bytes out;
    for (int64_t t = 0; t <= 2'000'000; t += 1000) d.tick(t, 38400, out);
    // 732 bytes take 190.6 ms: one scan every 8 periods (213.3 ms), the first at 26.7 ms:
    // 26.7 + 9 x 213.3 = 1946.7 ms, so 10 scans in 2 s.
    CHECK(parse(out).raws.size() == 10);
    CHECK(d.stats().scans_skipped > 60);
}

TEST_CASE("emulator: bit flips and garbage are caught by the CRC", "[lms][emulator]")
{
    sim::DeviceOptions o;
    o.initial_baud = 500000;
    o.faults.bitflip_probability = 0.5;
    o.faults.garbage_probability = 0.5;
    sim::LmsDevice d(o);
    ask(d, request_start_streaming(), 500000, 0);
    Bytes out;
    for (int64_t t = 0; t <= 2'000'000; t += 1000) d.tick(t, 500000, out);
    Decoder dec;
    int good = 0;
    dec.feed(out.data(), out.size(), [&](const DecoderEvent& ev) { good += ev.kind == K::telegram; });
    CHECK(d.stats().scans_sent == 75);
    CHECK(dec.stats().crc_errors > 20);
    CHECK(good + static_cast<int>(dec.stats().crc_errors) >= 75);
    CHECK(good < 60);
}

namespace {

// 2 s of streaming at 500000 baud from a device with these faults: the bytes it sent.
Bytes stream_2s(sim::LmsDevice& d)
{
    ask(d, request_start_streaming(), 500000, 0);
    Bytes out;
    for (int64_t t = 0; t <= 2'000'000; t += 1000) d.tick(t, 500000, out);
    return out;
}

sim::DeviceOptions at_500000(const sim::Faults& faults)
{
    sim::DeviceOptions o;
    o.initial_baud = 500000;
    o.faults = faults;
    o.seed = 11;
    return o;
}

}  // namespace

TEST_CASE("emulator: bit errors per byte damage that share of bytes, and only damaged scans fail", "[lms][emulator]")
{
    sim::LmsDevice clean(at_500000({}));
    const Reply reference = parse(stream_2s(clean));
    REQUIRE(reference.raws.size() == 75);
    const Bytes& intact = reference.raws.back();  // every scan of the static floor is the same

    for (const double rate : {1e-3, 1e-2}) {
        INFO("rate " << rate);
        sim::Faults f;
        f.bit_error_rate = rate;
        sim::LmsDevice d(at_500000(f));
        const Bytes out = stream_2s(d);
        // 75 scans of 732 bytes.
        const double share = static_cast<double>(d.stats().bytes_damaged) / static_cast<double>(out.size());
        CHECK(share > 0.6 * rate);
        CHECK(share < 1.4 * rate);
        Decoder dec;
        int good_scans = 0;
        dec.feed(out.data(), out.size(), [&](const DecoderEvent& ev) {
            if (ev.kind != K::telegram || ev.telegram.command != cmd::scan) return;
            ++good_scans;
            REQUIRE(Bytes(ev.telegram.raw.begin(), ev.telegram.raw.end()) == intact);
        });
        CHECK(dec.stats().crc_errors + dec.stats().resyncs > 0);
        // 732 bytes survive 1e-3 with p = 0.48 and 1e-2 with p = 0.0006.
        if (rate == 1e-3) {
            CHECK(good_scans >= 20);
            CHECK(good_scans <= 55);
        } else {
            CHECK(good_scans <= 2);
        }
    }
}

TEST_CASE("the LMS checksum misses bits b and b + 1 flipped in adjacent bytes (why 1e-2 lets some through)",
          "[lms][emulator]")
{
    sim::LmsDevice clean(at_500000({}));
    const Bytes intact = parse(stream_2s(clean)).raws.back();
    for (const std::size_t at : {std::size_t{7}, std::size_t{300}, intact.size() - 5}) {  // at + 2 still checked
        for (int b = 0; b < 7; ++b) {
            Bytes damaged = intact;
            damaged[at] ^= static_cast<uint8_t>(1u << b);
            damaged[at + 1] ^= static_cast<uint8_t>(1u << (b + 1));
            INFO("bytes " << at << ", " << at + 1 << ", bits " << b << ", " << b + 1);
            const Reply r = parse(damaged);
            REQUIRE(r.raws.size() == 1);
            CHECK(r.raws[0] == damaged);
        }
    }
}

TEST_CASE("emulator: truncated scans never decode, and the scan after each one does", "[lms][emulator]")
{
    sim::Faults f;
    f.truncate_probability = 0.3;
    sim::LmsDevice d(at_500000(f));
    const Bytes out = stream_2s(d);
    const uint64_t cut = d.stats().scans_truncated;
    CHECK(cut >= 10);
    CHECK(cut <= 40);
    REQUIRE(d.stats().scans_sent == 75);
    Decoder dec;
    uint64_t good_scans = 0;
    dec.feed(out.data(), out.size(), [&](const DecoderEvent& ev) {
        good_scans += ev.kind == K::telegram && ev.telegram.command == cmd::scan && ev.telegram.raw.size() == 732;
    });
    // All but the cut ones; the last good scan may be held back when a false frame start
    // inside the rejected bytes claims more than the stream has left.
    CHECK(good_scans + cut <= 75);
    CHECK(good_scans + cut >= 74);
    // Each cut frame claims 732 bytes and fails its CRC once the next frame has arrived (the
    // last one may still be waiting for bytes).
    CHECK(dec.stats().crc_errors + 1 >= cut);
    CHECK(dec.stats().crc_errors <= cut);
}

TEST_CASE("emulator: silence windows", "[lms][emulator]")
{
    sim::DeviceOptions o;
    o.initial_baud = 500000;
    o.faults.silence_every_s = 1.0;
    o.faults.silence_for_s = 0.5;
    sim::LmsDevice d(o);
    ask(d, request_start_streaming(), 500000, 0);
    Bytes first_half, second_half;
    for (int64_t t = 0; t < 500'000; t += 1000) d.tick(t, 500000, first_half);
    for (int64_t t = 500'000; t < 1'000'000; t += 1000) d.tick(t, 500000, second_half);
    CHECK(parse(first_half).raws.size() >= 17);
    CHECK(second_half.empty());
    CHECK(ask(d, request_type(), 500000, 700'000).empty());
    CHECK_FALSE(ask(d, request_type(), 500000, 1'100'000).empty());
}

TEST_CASE("emulator: --fault flags", "[lms][emulator]")
{
    sim::FaultPlan plan;
    sim::add_fault("garbage", plan);
    CHECK(plan.device.garbage_probability == 0.1);
    sim::add_fault("bitflip:0.25", plan);
    CHECK(plan.device.bitflip_probability == 0.25);
    sim::add_fault("silence:4:1.5", plan);
    CHECK(plan.device.silence_every_s == 4.0);
    CHECK(plan.device.silence_for_s == 1.5);
    sim::add_fault("disappear:3", plan);
    CHECK(plan.disappear_after_s == 3.0);
    CHECK(plan.disappear_for_s == 1.0);
    sim::add_fault("ber:0.01", plan);
    CHECK(plan.device.bit_error_rate == 0.01);
    sim::add_fault("truncate", plan);
    CHECK(plan.device.truncate_probability == 0.1);
    CHECK_THROWS_WITH(sim::add_fault("smoke", plan),
                      "--fault smoke: unknown fault (garbage, bitflip, ber, truncate, silence, disappear)");
    CHECK_THROWS(sim::add_fault("ber:1.5", plan));
    CHECK_THROWS(sim::add_fault("garbage:2", plan));
    CHECK_THROWS(sim::add_fault("garbage:x", plan));
    CHECK_THROWS(sim::add_fault("silence:1:2", plan));  // silent longer than the period
    CHECK_THROWS(sim::add_fault("bitflip:0.1:3", plan));
}

namespace {
// The beam times the emulator asked its scene for, for its first scan: sent one scan period
// after streaming started at 0 (26666 us at 0.5 deg, 53333 us at 0.25 deg).
std::vector<double> beam_times_of_first_scan(sim::DeviceOptions o, int angle_deg = 180, int resolution_cdeg = 50)
{
    std::vector<double> times;
    o.initial_baud = 500000;
    o.beam_scene = [&times](double, int64_t t) {
        times.push_back(static_cast<double>(t));
        return 2.0;
    };
    sim::LmsDevice d(o);
    if (resolution_cdeg != 50) ask(d, request_variant(angle_deg, resolution_cdeg), 500000, 0);
    ask(d, request_start_streaming(), 500000, 0);
    Bytes out;
    d.tick(static_cast<int64_t>(scan_period_s(resolution_cdeg) * 1e6), 500000, out);
    REQUIRE(parse(out).raws.size() == 1);
    return times;
}
}  // namespace

TEST_CASE("emulator: beam times follow the mirror's interlaced sweeps", "[lms][emulator]")
{
    // 361 values = 732 bytes, 14640 us at 500000 baud: the last beam at 26666 - 14640 = 12026.
    // The scan started a turn (13333.3 us) and a 180 deg crossing (6666.7 us) before it.
    constexpr double kStart = 12026.0 - 20000.0;
    constexpr double kTurn = 1e6 / 75.0;
    SECTION("0.5 deg, even beams first (the default)")
    {
        const std::vector<double> t = beam_times_of_first_scan({});
        REQUIRE(t.size() == 361);
        for (int i = 0; i < 361; ++i)
            CHECK(t[static_cast<std::size_t>(i)] == Approx(kStart + (i % 2) * kTurn + i * 0.5 * kTurn / 360.0).margin(0.6));
        CHECK(t[360] == Approx(kStart + 6666.7).margin(1));  // the last even beam ends sweep 0
        CHECK(t[359] - t[358] == Approx(13333.3 + 18.5).margin(1));
    }
    SECTION("0.5 deg, odd beams first")
    {
        sim::DeviceOptions o;
        REQUIRE(sim::set_sweep_order(o, "10"));
        const std::vector<double> t = beam_times_of_first_scan(o);
        CHECK(t[1] == Approx(kStart + 18.5).margin(0.6));
        CHECK(t[0] == Approx(kStart + 13333.3).margin(0.6));
        CHECK(t[360] == Approx(12026.0).margin(0.6));  // the last beam measured
    }
    SECTION("0.25 deg over 100 deg, four sweeps in the order 2031")
    {
        sim::DeviceOptions o;
        REQUIRE(sim::set_sweep_order(o, "2031"));
        const std::vector<double> t = beam_times_of_first_scan(o, 100, 25);
        REQUIRE(t.size() == 401);
        // 401 values = 812 bytes (16240 us); the scan starts 3 turns and a 100 deg crossing
        // (3703.7 us) before its last beam, which the telegram follows.
        const double start = 53333.0 - 16240.0 - 3 * kTurn - 3703.7;
        const int sweep_of_phase[4] = {1, 3, 0, 2};
        for (int i = 0; i < 401; ++i)
            CHECK(t[static_cast<std::size_t>(i)] ==
                  Approx(start + sweep_of_phase[i % 4] * kTurn + i * 0.25 * kTurn / 360.0).margin(0.6));
    }
    SECTION("linear timing, for comparison: angle order over the whole scan period")
    {
        sim::DeviceOptions o;
        o.linear_timing = true;
        const std::vector<double> t = beam_times_of_first_scan(o);
        CHECK(t[0] == Approx(12026.0 - 2 * kTurn).margin(0.6));
        CHECK(t[1] - t[0] == Approx(74.07).margin(1));
        CHECK(t[360] == Approx(12026.0).margin(0.6));
    }
    CHECK_FALSE(sim::set_sweep_order(*std::make_unique<sim::DeviceOptions>(), "011"));
    CHECK_FALSE(sim::set_sweep_order(*std::make_unique<sim::DeviceOptions>(), "0113"));
}
