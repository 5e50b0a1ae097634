#include <catch2/catch.hpp>

#include "ugv/microstrain_gx1/tick_unwrapper.hpp"

using ugv::microstrain_gx1::TickUnwrapper;

TEST_CASE("u16 timer unwraps across the wrap", "[gx1][ticks]")
{
    TickUnwrapper u;
    CHECK(u.unwrap(65530) == 65530);
    CHECK(u.unwrap(65535) == 65535);
    CHECK(u.unwrap(3) == 65539);        // wrapped: 65536 + 3
    CHECK(u.unwrap(40000) == 65536 + 40000);
    CHECK(u.unwrap(10) == 2 * 65536 + 10);  // a second wrap
    u.reset();
    CHECK(u.unwrap(7) == 7);
}
