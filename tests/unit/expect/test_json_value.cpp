#include <catch2/catch.hpp>

#include "ugv/expect/json_value.hpp"

using ugv::expect::JsonValue;
using ugv::expect::parse_json;

TEST_CASE("JSON documents as ugv::reflect prints them parse into values")
{
    const auto v = parse_json(R"({"utime":1000,"seq":-3,"name":"a\"b\u0041","ranges":[1.5,null,2e3],"ok":true,"pose":{"x":[0,1]}})");
    REQUIRE(v);
    REQUIRE(v->kind == JsonValue::Kind::object);
    CHECK(v->object.at("utime").number == 1000);
    CHECK(v->object.at("seq").number == -3);
    CHECK(v->object.at("name").string == "a\"bA");
    const auto& r = v->object.at("ranges").array;
    REQUIRE(r.size() == 3);
    CHECK(r[0].number == 1.5);
    CHECK(r[1].kind == JsonValue::Kind::null);
    CHECK(r[2].number == 2000);
    CHECK(v->object.at("ok").boolean);
    CHECK(v->object.at("pose").object.at("x").array[1].number == 1);
    CHECK(parse_json("[]")->array.empty());
    CHECK_FALSE(parse_json("false")->boolean);
}

TEST_CASE("malformed JSON is refused")
{
    for (const char* bad : {"", "{", "{\"a\":}", "[1,]", "{\"a\" 1}", "\"open", "{} x", "nul"}) CHECK_FALSE(parse_json(bad));
}
