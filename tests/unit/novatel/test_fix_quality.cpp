#include <catch2/catch.hpp>

#include "ugv/novatel/enums.hpp"
#include "ugv/novatel/fix_quality.hpp"

using namespace ugv::novatel;

TEST_CASE("position type -> fix quality")
{
    const uint32_t ok = solution_status::sol_computed;
    CHECK(quality_from_position_type(ok, position_type::none) == FixQuality::none);
    CHECK(quality_from_position_type(ok, position_type::single) == FixQuality::single);
    CHECK(quality_from_position_type(ok, position_type::waas) == FixQuality::sbas);
    CHECK(quality_from_position_type(ok, position_type::psrdiff) == FixQuality::dgps);
    CHECK(quality_from_position_type(ok, position_type::omnistar_hp) == FixQuality::dgps);
    CHECK(quality_from_position_type(ok, position_type::narrow_float) == FixQuality::rtk_float);
    CHECK(quality_from_position_type(ok, position_type::l1_float) == FixQuality::rtk_float);
    CHECK(quality_from_position_type(ok, position_type::narrow_int) == FixQuality::rtk_fixed);
    CHECK(quality_from_position_type(ok, position_type::l1_int) == FixQuality::rtk_fixed);
    CHECK(quality_from_position_type(ok, position_type::propagated) == FixQuality::dead_reckoning);
    CHECK(quality_from_position_type(ok, 53) == FixQuality::single);  // INS_PSRSP
    CHECK(quality_from_position_type(ok, 56) == FixQuality::rtk_fixed);  // INS_RTKFIXED
    CHECK(quality_from_position_type(ok, position_type::fixedpos) == FixQuality::unknown);
    CHECK(quality_from_position_type(ok, 74) == FixQuality::unknown);  // newer than our table
    CHECK(quality_from_position_type(ok, kUnknownEnum) == FixQuality::unknown);
    // No computed solution: no fix, whatever the type says.
    CHECK(quality_from_position_type(solution_status::insufficient_obs, position_type::single) == FixQuality::none);
}

TEST_CASE("GGA quality -> fix quality")
{
    CHECK(quality_from_gga(0) == FixQuality::none);
    CHECK(quality_from_gga(1) == FixQuality::single);
    CHECK(quality_from_gga(2) == FixQuality::dgps);
    CHECK(quality_from_gga(4) == FixQuality::rtk_fixed);
    CHECK(quality_from_gga(5) == FixQuality::rtk_float);
    CHECK(quality_from_gga(6) == FixQuality::dead_reckoning);
    CHECK(quality_from_gga(7) == FixQuality::unknown);
    CHECK(quality_from_gga(8) == FixQuality::unknown);
    CHECK(quality_from_gga(9) == FixQuality::sbas);
    CHECK(quality_from_gga(42) == FixQuality::unknown);
}

TEST_CASE("enum names round-trip; unknown values have no name")
{
    CHECK(position_type_name(50).value() == "NARROW_INT");
    CHECK(position_type_from_name("NARROW_INT") == 50);
    CHECK(solution_status_from_name("SOL_COMPUTED") == 0);
    CHECK(time_status_from_name("FINESTEERING") == 180);
    CHECK(time_status_name(200).value() == "SATTIME");
    CHECK_FALSE(position_type_name(74).has_value());
    CHECK(position_type_from_name("INS_PPP") == kUnknownEnum);
}
