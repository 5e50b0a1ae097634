#include <catch2/catch.hpp>

#include "ugv/expect/where_expression.hpp"

using ugv::expect::parse_json;
using ugv::expect::WhereExpression;

TEST_CASE("--where conditions are evaluated on message fields")
{
    const auto f = *parse_json(R"({"seq":7,"sensor_id":"front","ranges":[1.5,null,3],"pose":{"position":[10,-2,0]},"fault":false})");
    CHECK(WhereExpression("ranges.size() == 3").matches(f));
    CHECK_FALSE(WhereExpression("ranges.size() == 361").matches(f));
    CHECK(WhereExpression("seq >= 7 && seq < 8").matches(f));
    CHECK(WhereExpression("pose.position[1] < -1.5").matches(f));
    CHECK(WhereExpression("sensor_id == \"front\"").matches(f));
    CHECK(WhereExpression("sensor_id.size() == 5").matches(f));
    CHECK(WhereExpression("fault == false").matches(f));
    CHECK(WhereExpression("fault == 0").matches(f));
    CHECK_FALSE(WhereExpression("ranges[1] > 0").matches(f));  // NaN compares false
    CHECK(WhereExpression("ranges[1] != 0").matches(f));
    CHECK_FALSE(WhereExpression("ranges[9] > 0").matches(f));  // out of range: false, not a crash
    CHECK_FALSE(WhereExpression("nosuch == 1").matches(f));
}

TEST_CASE("malformed --where conditions are refused with a reason")
{
    CHECK_THROWS_WITH(WhereExpression("seq 7"), "no comparison (== != < <= > >=) in 'seq 7'");
    CHECK_THROWS_WITH(WhereExpression("seq == seven"), "'seven' is not a number, true/false or a \"string\"");
    CHECK_THROWS_WITH(WhereExpression("seq == 1 &&"), "empty condition in 'seq == 1 &&'");
    CHECK_THROWS_WITH(WhereExpression("ranges[x] == 1"), "bad index in 'ranges[x]'");
}
