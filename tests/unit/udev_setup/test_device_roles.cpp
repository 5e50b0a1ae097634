#include <catch2/catch.hpp>

#include "ugv/runtime/config.hpp"
#include "ugv/udev_setup/device_roles.hpp"

using namespace ugv::udev_setup;

namespace {
std::string config_error(const std::string& text)
{
    try {
        parse_roles(text, "devices.conf");
    } catch (const ugv::runtime::ConfigError& e) {
        return e.what();
    }
    return "";
}
}  // namespace

TEST_CASE("--role flags: ids in either case, serial optional, one-line errors")
{
    const auto r = parse_role_flag("lms-front=0403:6001:FTLMS001");
    CHECK(r.role == "lms-front");
    CHECK(format_usb_id(r.id) == "0403:6001:FTLMS001");
    CHECK(format_usb_id(parse_role_flag("can.servo=AD50:60C4").id) == "ad50:60c4");
    CHECK_THROWS_WITH(parse_role_flag("lms"), Catch::Contains("ROLE=VENDOR:PRODUCT"));
    CHECK_THROWS_WITH(parse_role_flag("lms=403:6001"), Catch::Contains("vendor '403'"));
    CHECK_THROWS_WITH(parse_role_flag("lms=0403:60x1:A"), Catch::Contains("product '60x1'"));
    CHECK_THROWS_WITH(parse_role_flag("lms=0403:6001:"), Catch::Contains("empty serial"));
    CHECK_THROWS_WITH(parse_role_flag("lms=0403:6001:A B"), Catch::Contains("as udev sees it: 'A_B'"));
    CHECK_THROWS_WITH(parse_role_flag("../x=0403:6001"), Catch::Contains("must start with a letter or digit"));
    CHECK_THROWS_WITH(parse_role_flag("lms/front=0403:6001"), Catch::Contains("only letters, digits"));
    CHECK_THROWS_WITH(parse_role_flag("=0403:6001"), Catch::Contains("empty role"));
}

TEST_CASE("serials as udev's usb_id has them")
{
    CHECK(udev_serial("  A50285BI \n") == "A50285BI");
    CHECK(udev_serial("GX1 \t 0001") == "GX1_0001");
    CHECK(udev_serial("a/b\xc3\xa9") == "a_b__");
    CHECK(udev_serial("x#+-.:=@_y") == "x#+-.:=@_y");
    CHECK(udev_serial(" ") == "");
}

TEST_CASE("the roles file round-trips and rejects what udev could not use")
{
    const std::string text = "# comment\n\nlms-front 0403:6001:FTLMS001   # the front laser\n  can-servo ad50:60c4\n";
    const auto roles = parse_roles(text, "devices.conf");
    REQUIRE(roles.size() == 2);
    CHECK(roles[1].role == "can-servo");
    CHECK(roles[1].id.serial.empty());
    CHECK(parse_roles(format_roles(roles), "x").size() == 2);
    CHECK(format_roles(parse_roles(format_roles(roles), "x")) == format_roles(roles));

    CHECK(config_error("lms\n") == "devices.conf: line 1: 'lms' has no VENDOR:PRODUCT[:SERIAL]");
    CHECK(config_error("\nlms 0403:6001 extra\n") == "devices.conf: line 2: unexpected 'extra' after the adapter");
    CHECK(config_error("lms 0403:6001:A\nlms 0403:6001:B\n") == "devices.conf: line 2: role 'lms' is given twice");
    CHECK(config_error("a 0403:6001:A\nb 0403:6001:A\n") ==
          "devices.conf: line 2: roles 'a' and 'b' name the same adapter 0403:6001:A");
    CHECK(config_error("lms 0403-6001\n") ==
          "devices.conf: line 1: '0403-6001' is not VENDOR:PRODUCT[:SERIAL] (e.g. 0403:6001:A50285BI)");
}

TEST_CASE("lookup: an exact serial wins over a role without one")
{
    const auto roles = parse_roles("spare 0403:6001\nlms-front 0403:6001:FTLMS001\ngps 0403:6001:FTGPS001\n", "x");
    CHECK(lookup_role(roles, {"0403", "6001", "FTGPS001"}) == "gps");
    CHECK(lookup_role(roles, {"0403", "6001", "FTLMS001"}) == "lms-front");
    CHECK(lookup_role(roles, {"0403", "6001", "OTHER"}) == "spare");
    CHECK(lookup_role(roles, {"0403", "6001", ""}) == "spare");
    CHECK(lookup_role(roles, {"067B", "2303", "X"}) == std::nullopt);
    CHECK(lookup_role(parse_roles("imu 067b:2303:X\n", "x"), {"067B", "2303", "X"}) == "imu");
}

TEST_CASE("merging flags into the file: replace in place, append, no two roles on one adapter")
{
    auto roles = parse_roles("lms-front 0403:6001:A\ngps 0403:6001:B\n", "x");
    roles = merge_roles(roles, {parse_role_flag("gps=0403:6001:C"), parse_role_flag("imu=067b:2303")});
    CHECK(format_roles(roles).ends_with("lms-front 0403:6001:A\ngps 0403:6001:C\nimu 067b:2303\n"));
    CHECK_THROWS_WITH(merge_roles(roles, {parse_role_flag("lms-rear=0403:6001:A")}),
                      "roles 'lms-front' and 'lms-rear' name the same adapter 0403:6001:A");
}
