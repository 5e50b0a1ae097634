#include <catch2/catch.hpp>

#include "ugv/runtime/backoff.hpp"

TEST_CASE("back-off doubles up to its cap and starts over after reset")
{
    ugv::runtime::Backoff b(100'000, 1'000'000);
    CHECK(b.next() == 100'000);
    CHECK(b.next() == 200'000);
    CHECK(b.next() == 400'000);
    CHECK(b.next() == 800'000);
    CHECK(b.next() == 1'000'000);
    CHECK(b.next() == 1'000'000);
    b.reset();
    CHECK(b.next() == 100'000);
}
