// Reply decoding and the scan timing / time stamp model.
#include <catch2/catch.hpp>

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

TEST_CASE("first-beam stamp = arrival - transmission - scan duration", "[sick_lms2xx][timing]")
{
    // 361 values at 500000 baud: 732 bytes take 14.64 ms; the scan lasts 26.667 ms.
    const ScanStamp s = stamp_scan(1'700'000'000'000'000, 732, 500000, scan_period_s(50), 361);
    CHECK(s.first_beam_utime == 1'700'000'000'000'000 - 14640 - 26667);
    CHECK(s.time_increment_s == Approx(scan_period_s(50) / 360.0));
    // At 38400 baud the same telegram takes 190.625 ms.
    const ScanStamp slow = stamp_scan(1'000'000, 732, 38400, scan_period_s(50), 361);
    CHECK(slow.first_beam_utime == 1'000'000 - 190625 - 26667);
    CHECK(stamp_scan(0, 0, 500000, 0.01, 1).time_increment_s == 0.0);
}
