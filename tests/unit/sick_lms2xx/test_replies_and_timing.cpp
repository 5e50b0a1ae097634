// Reply decoding and the scan timing / time stamp model.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "ugv/sick_lms2xx/decoder.hpp"
#include "ugv/sick_lms2xx/replies.hpp"
#include "ugv/sick_lms2xx/timing.hpp"

using namespace ugv::sick_lms2xx;
using Bytes = std::vector<uint8_t>;

namespace {
template <typename F>
void with_telegram(const Bytes& frame, F&& f)
{
    Decoder dec;
    int n = 0;
    dec.feed(frame.data(), frame.size(), [&](const DecoderEvent& ev) {
        if (ev.kind != DecoderEvent::Kind::telegram) return;
        ++n;
        f(ev.telegram);
    });
    REQUIRE(n == 1);
}
}  // namespace

TEST_CASE("mode reply 0xA0", "[sick_lms2xx][replies]")
{
    with_telegram(encode_reply(0xA0, Bytes{0x00}, 0x10), [](const Telegram& t) { CHECK(decode_mode_reply(t) == kModeOk); });
    with_telegram(encode_reply(0xA0, Bytes{0x01}, 0x10),
                  [](const Telegram& t) { CHECK(decode_mode_reply(t) == kModeBadPassword); });
    with_telegram(encode_reply(0xBB, Bytes{0x01}, 0x10), [](const Telegram& t) { CHECK_FALSE(decode_mode_reply(t)); });
}

TEST_CASE("variant reply 0xBB", "[sick_lms2xx][replies]")
{
    with_telegram(encode_reply(0xBB, Bytes{0x01, 0xB4, 0x00, 0x32, 0x00}, 0x10), [](const Telegram& t) {
        const auto r = decode_variant_reply(t);
        REQUIRE(r);
        CHECK(r->accepted);
        CHECK(r->angle_deg == 180);
        CHECK(r->resolution_cdeg == 50);
    });
    with_telegram(encode_reply(0xBB, Bytes{0x00}, 0x10), [](const Telegram& t) {
        const auto r = decode_variant_reply(t);
        REQUIRE(r);
        CHECK_FALSE(r->accepted);
    });
}

TEST_CASE("configuration read 0xF4 and write 0xF7", "[sick_lms2xx][replies]")
{
    Bytes block(32, 0);
    block[4] = 0x02;
    block[5] = 0x06;
    block[6] = 0x01;
    with_telegram(encode_reply(0xF4, block, 0x10), [&](const Telegram& t) {
        auto c = decode_config_reply(t);
        REQUIRE(c);
        CHECK(c->block == block);
        CHECK(c->availability() == 0x02);
        CHECK(c->measuring_mode() == 0x06);
        CHECK(c->units() == kConfigUnitsMm);
        c->set_units(kConfigUnitsCm);
        CHECK(c->block[6] == 0x00);
    });
    with_telegram(encode_reply(0xF4, Bytes(6, 0), 0x10), [](const Telegram& t) { CHECK_FALSE(decode_config_reply(t)); });
    Bytes echo = {0x01};
    echo.insert(echo.end(), block.begin(), block.end());
    with_telegram(encode_reply(0xF7, echo, 0x10), [](const Telegram& t) { CHECK(decode_write_config_reply(t) == true); });
    with_telegram(encode_reply(0xF7, Bytes{0x00}, 0x10),
                  [](const Telegram& t) { CHECK(decode_write_config_reply(t) == false); });
}

TEST_CASE("type, status and reset replies", "[sick_lms2xx][replies]")
{
    const std::string type = "LMS200;30106";
    with_telegram(encode_reply(0xBA, Bytes(type.begin(), type.end()), 0x10),
                  [&](const Telegram& t) { CHECK(decode_type_reply(t) == type); });
    const std::string status = "V02.10 plus more";
    with_telegram(encode_reply(0xB1, Bytes(status.begin(), status.end()), 0x10), [](const Telegram& t) {
        const auto r = decode_status_reply(t);
        REQUIRE(r);
        CHECK(r->version == "V02.10 ");
        CHECK(r->block.size() == 16);
    });
    with_telegram(encode_reply(0x91, Bytes{}, 0x10), [](const Telegram& t) { CHECK(is_reset_reply(t)); });
}

TEST_CASE("scan timing per variant", "[sick_lms2xx][timing]")
{
    CHECK(scan_period_s(100) == Approx(1.0 / 75.0));
    CHECK(scan_period_s(50) == Approx(0.0266667).epsilon(1e-4));
    CHECK(scan_period_s(25) == Approx(0.0533333).epsilon(1e-4));
    CHECK(beams_per_scan(180, 100) == 181);
    CHECK(beams_per_scan(180, 50) == 361);
    CHECK(beams_per_scan(100, 25) == 401);
    CHECK(beams_per_scan(100, 50) == 201);
    CHECK(line_time_s(732, 500000) == Approx(0.01464));
    CHECK(line_time_s(732, 38400) == Approx(0.190625));
}

TEST_CASE("the last sweep ends one transmission time before the telegram's last byte", "[sick_lms2xx][timing]")
{
    // 361 values at 500000 baud: 732 bytes take 14.64 ms; at 38400 baud 190.625 ms.
    CHECK(scan_end_utime(1'700'000'000'000'000, 732, 500000) == 1'700'000'000'000'000 - 14640);
    CHECK(scan_end_utime(1'000'000, 732, 38400) == 1'000'000 - 190625);
}

namespace {
// Microseconds from the scan's start to beam i.
double offset_us(const ScanStamp& s, int i) { return s.beam_offset_s(i) * 1e6; }
constexpr int64_t kLast = 1'000'000'000;  // the end of the last sweep
}  // namespace

TEST_CASE("beam times at 0.5 deg follow the mirror, both sweep orders", "[sick_lms2xx][timing]")
{
    // One turn 13333.33 us; the 180 deg field takes 6666.67 us; 0.5 deg = 18.519 us.
    // The scan starts one turn plus one field crossing before its last beam: 20000 us.
    const ScanStamp even_first = stamp_scan(kLast, 180, 50, BeamTiming::interlaced, parse_sweep_order("01", 50));
    CHECK(even_first.first_beam_utime == kLast - 20000);
    CHECK(even_first.sweep_period_s == Approx(1.0 / 75.0));
    CHECK(even_first.time_increment_s * 1e6 == Approx(18.5185).epsilon(1e-5));
    CHECK(offset_us(even_first, 0) == Approx(0.0).margin(1e-9));
    CHECK(offset_us(even_first, 1) == Approx(13351.852).epsilon(1e-7));
    CHECK(offset_us(even_first, 2) == Approx(37.037).epsilon(1e-5));
    CHECK(offset_us(even_first, 359) == Approx(19981.481).epsilon(1e-7));
    CHECK(offset_us(even_first, 360) == Approx(6666.667).epsilon(1e-7));

    const ScanStamp odd_first = stamp_scan(kLast, 180, 50, BeamTiming::interlaced, parse_sweep_order("10", 50));
    CHECK(odd_first.first_beam_utime == kLast - 20000);
    CHECK(offset_us(odd_first, 0) == Approx(13333.333).epsilon(1e-7));
    CHECK(offset_us(odd_first, 1) == Approx(18.519).epsilon(1e-4));
    CHECK(offset_us(odd_first, 359) == Approx(6648.148).epsilon(1e-7));
    CHECK(offset_us(odd_first, 360) == Approx(20000.0).epsilon(1e-7));  // the very last beam
    // Neighbours are a sweep apart, whichever order.
    CHECK(std::abs(offset_us(odd_first, 181) - offset_us(odd_first, 180)) == Approx(13333.333 - 18.519).epsilon(1e-6));
}

TEST_CASE("beam times at 0.25 deg follow the mirror, natural and shuffled orders", "[sick_lms2xx][timing]")
{
    // Four sweeps; the 100 deg field takes 3703.70 us; 0.25 deg = 9.259 us. Start: 3 turns
    // plus one field crossing before the last beam = 43703.70 us.
    const ScanStamp natural = stamp_scan(kLast, 100, 25, BeamTiming::interlaced, parse_sweep_order("", 25));
    CHECK(natural.first_beam_utime == kLast - 43704);
    CHECK(natural.order.sweeps == 4);
    CHECK(offset_us(natural, 4) == Approx(37.037).epsilon(1e-5));
    CHECK(offset_us(natural, 5) == Approx(13379.630).epsilon(1e-7));
    CHECK(offset_us(natural, 399) == Approx(43694.444).epsilon(1e-7));

    // Sweep 0 takes phase 2, sweep 1 phase 0, sweep 2 phase 3, sweep 3 phase 1.
    const ScanStamp shuffled = stamp_scan(kLast, 100, 25, BeamTiming::interlaced, parse_sweep_order("2031", 25));
    CHECK(offset_us(shuffled, 6) == Approx(55.556).epsilon(1e-5));
    CHECK(offset_us(shuffled, 400) == Approx(17037.037).epsilon(1e-7));
    CHECK(offset_us(shuffled, 3) == Approx(26694.444).epsilon(1e-7));
    CHECK(offset_us(shuffled, 5) == Approx(40046.296).epsilon(1e-7));
    CHECK(shuffled.order.sweep_of_beam(5) == 3);
}

TEST_CASE("the linear model spreads the beams over the scan period", "[sick_lms2xx][timing]")
{
    const ScanStamp s = stamp_scan(kLast, 180, 50, BeamTiming::linear, parse_sweep_order("10", 50));
    CHECK(s.first_beam_utime == kLast - 26667);
    CHECK(s.order.sweeps == 1);
    CHECK(offset_us(s, 1) == Approx(74.074).epsilon(1e-5));
    CHECK(offset_us(s, 360) == Approx(26666.667).epsilon(1e-7));
    // 1 deg: one sweep, the field crossed in 6666.67 us by the mirror model.
    const ScanStamp one = stamp_scan(kLast, 180, 100, BeamTiming::interlaced, parse_sweep_order("", 100));
    CHECK(one.first_beam_utime == kLast - 6667);
    CHECK(offset_us(one, 180) == Approx(6666.667).epsilon(1e-7));
}

TEST_CASE("sweep orders are parsed and refused with one line", "[sick_lms2xx][timing]")
{
    CHECK(to_string(parse_sweep_order("", 50)) == "01");
    CHECK(to_string(parse_sweep_order("", 25)) == "0123");
    CHECK(to_string(parse_sweep_order("", 100)) == "0");
    CHECK(to_string(parse_sweep_order("3120", 25)) == "3120");
    const auto reason = [](const std::string& text, int res) {
        try {
            (void)parse_sweep_order(text, res);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(reason("012", 50) == "\"012\" has 3 digits; a 0.5 deg scan has 2 sweeps (e.g. \"01\" or \"10\")");
    CHECK(reason("11", 50).find("not an order of the beam phases 0..1") != std::string::npos);
    CHECK(reason("0124", 25).find("not an order") != std::string::npos);
    CHECK(reason("a1", 50).find("not an order") != std::string::npos);
    CHECK(reason("10", 100).find("1 sweeps") != std::string::npos);
}
