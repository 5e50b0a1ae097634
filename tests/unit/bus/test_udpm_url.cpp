// The receiving side's reading of LCM udpm URLs.
#include <catch2/catch.hpp>

#include "ugv/bus/udpm_url.hpp"
#include "ugv/bus/bus.hpp"

using ugv::bus::detail::parse_udpm_url;

TEST_CASE("udpm url: address, port and options; liblcm's defaults where left out")
{
    const auto u = parse_udpm_url("udpm://239.255.76.68:7315?ttl=1&recv_buf_size=2097152");
    REQUIRE(u);
    CHECK(u->group == "239.255.76.68");
    CHECK(u->port == 7315);
    CHECK(u->ttl == 1);
    CHECK(u->recv_buf_size == 2097152);
    CHECK_FALSE(u->transmit_only);
    const auto d = parse_udpm_url("udpm://");
    REQUIRE(d);
    CHECK(d->group == "239.255.76.67");
    CHECK(d->port == 7667);
    CHECK(d->recv_buf_size == 0);
    CHECK(parse_udpm_url("udpm://239.255.76.67:7667?transmit_only=true")->transmit_only);
    CHECK(parse_udpm_url("udpm://239.255.76.67:7667?ttl=0&")->ttl == 0);
}

TEST_CASE("udpm url: another provider is not ours")
{
    CHECK_FALSE(parse_udpm_url("memq://"));
    CHECK_FALSE(parse_udpm_url("file:///tmp/x.lcm?speed=0"));
}

TEST_CASE("udpm url: a malformed URL is refused with the URL and what is wrong")
{
    CHECK_THROWS_WITH(parse_udpm_url("udpm://239.255.76.67:70000"),
                      "LCM URL 'udpm://239.255.76.67:70000': port must be 1..65535");
    CHECK_THROWS_WITH(parse_udpm_url("udpm://239.255.76.67:76x"), Catch::Contains("port must be 1..65535"));
    CHECK_THROWS_WITH(parse_udpm_url("udpm://:7667"), Catch::Contains("no multicast address"));
    CHECK_THROWS_WITH(parse_udpm_url("udpm://239.255.76.67:7667?ttl=256"), Catch::Contains("ttl must be 0..255"));
    CHECK_THROWS_WITH(parse_udpm_url("udpm://239.255.76.67:7667?recv_buf_sise=1"),
                      Catch::Contains("unknown option 'recv_buf_sise'"));
    CHECK_THROWS_WITH(parse_udpm_url("udpm://239.255.76.67:7667?ttl"), Catch::Contains("option 'ttl' has no value"));
    CHECK_THROWS_AS(parse_udpm_url("udpm://239.255.76.67:7667?recv_buf_size=-5"), ugv::bus::BusError);
}
