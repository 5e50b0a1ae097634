#include <catch2/catch.hpp>

#include "frame_helpers.hpp"
#include "ugv/canopen/pdo.hpp"

using namespace ugv::canopen;
using canopen_test::frame;
using canopen_test::text;

namespace {
PdoMapping statusword_and_position()
{
    PdoMapping m;
    m.transmit = true;
    m.number = 1;
    m.transmission_type = kTransmissionEvent;
    m.event_timer_ms = 10;
    m.objects = {{0x6041, 0, 16}, {0x6064, 0, 32}};
    return m;
}
}  // namespace

TEST_CASE("TPDO configuration is the CiA 301 sequence")
{
    const auto w = pdo_configuration(statusword_and_position(), 2);
    const std::vector<SdoWrite> expected = {
        {{0x1800, 1}, 0x80000182u, 4},  // disable
        {{0x1800, 2}, 0xFF, 1},         // event driven
        {{0x1800, 5}, 10, 2},           // event timer 10 ms
        {{0x1A00, 0}, 0, 1},            // clear the mapping
        {{0x1A00, 1}, 0x60410010u, 4},
        {{0x1A00, 2}, 0x60640020u, 4},
        {{0x1A00, 0}, 2, 1},
        {{0x1800, 1}, 0x00000182u, 4},  // enable
    };
    CHECK(w == expected);
}

TEST_CASE("RPDO configuration uses 0x1400/0x1600 and has no event timer")
{
    PdoMapping m;
    m.transmit = false;
    m.number = 2;
    m.objects = {{0x6081, 0, 32}};
    const auto w = pdo_configuration(m, 5);
    REQUIRE(w.size() == 6);
    CHECK(w[0] == SdoWrite{{0x1401, 1}, 0x80000305u, 4});
    CHECK(w[3] == SdoWrite{{0x1601, 1}, 0x60810020u, 4});
    CHECK(w[5] == SdoWrite{{0x1401, 1}, 0x00000305u, 4});
}

TEST_CASE("PDO payloads pack and unpack little-endian in mapping order")
{
    const auto m = statusword_and_position();
    const auto f = pack_pdo(m, 2, {0x0237, static_cast<uint32_t>(-1000)});
    CHECK(text(f) == "182#370218FCFFFF");
    const auto v = unpack_pdo(m, 2, frame("182#371218FCFFFF"));
    REQUIRE(v);
    CHECK((*v)[0] == 0x1237u);
    CHECK(static_cast<int32_t>((*v)[1]) == -1000);
    CHECK_FALSE(unpack_pdo(m, 2, frame("182#3712")));        // too short
    CHECK_FALSE(unpack_pdo(m, 3, frame("182#371218FCFFFF")));  // another node
}
