#include <catch2/catch.hpp>

#include "ugv/canopen/cia402.hpp"

using namespace ugv::canopen::cia402;

TEST_CASE("States from the statusword (CiA 402 masks)")
{
    CHECK(state_from_statusword(0x0000) == State::not_ready_to_switch_on);
    CHECK(state_from_statusword(0x0250) == State::switch_on_disabled);
    CHECK(state_from_statusword(0x0231) == State::ready_to_switch_on);
    CHECK(state_from_statusword(0x0233) == State::switched_on);
    CHECK(state_from_statusword(0x0237) == State::operation_enabled);
    CHECK(state_from_statusword(0x1637) == State::operation_enabled);  // with set-point ack, target reached
    CHECK(state_from_statusword(0x0217) == State::quick_stop_active);
    CHECK(state_from_statusword(0x021F) == State::fault_reaction_active);
    CHECK(state_from_statusword(0x0218) == State::fault);
    CHECK(state_from_statusword(0x0208) == State::fault);
}

TEST_CASE("Controlwords as the drive reads them")
{
    CHECK(command_from_controlword(0x0006, 0) == Command::shutdown);
    CHECK(command_from_controlword(0x0007, 0x06) == Command::switch_on);
    CHECK(command_from_controlword(0x000F, 0x07) == Command::enable_operation);
    CHECK(command_from_controlword(0x003F, 0x0F) == Command::enable_operation);  // with set-point bits
    CHECK(command_from_controlword(0x0000, 0x0F) == Command::disable_voltage);
    CHECK(command_from_controlword(0x0002, 0x0F) == Command::quick_stop);
    CHECK(command_from_controlword(0x0080, 0x00) == Command::fault_reset);
    CHECK(command_from_controlword(0x0080, 0x80) == Command::none);  // no edge
}

TEST_CASE("Enabler walks switch on disabled -> operation enabled with 0x06, 0x07, 0x0F")
{
    Enabler e;
    e.set_goal(true, 0);
    CHECK(e.on_statusword(0x0250, 1000) == cw::shutdown);
    CHECK(e.on_statusword(0x0250, 2000) == cw::shutdown);
    CHECK(e.on_statusword(0x0231, 3000) == cw::switch_on);
    CHECK(e.on_statusword(0x0233, 4000) == cw::enable_operation);
    CHECK_FALSE(e.reached());
    CHECK(e.on_statusword(0x0237, 5000) == cw::enable_operation);
    CHECK(e.reached());
    CHECK_FALSE(e.check_timeout(10'000'000));  // reached: nothing to retry
    // Towards the power stage off.
    e.set_goal(false, 6000);
    CHECK(e.command() == cw::shutdown);
    CHECK(e.on_statusword(0x0231, 7000) == cw::shutdown);
    CHECK(e.reached());
}

TEST_CASE("Enabler resets a fault with a rising edge of bit 7, then enables")
{
    Enabler e;
    e.set_goal(true, 0);
    e.on_statusword(0x0237, 0);
    CHECK(e.on_statusword(0x021F, 1000) == cw::enable_operation);  // fault reaction: wait
    CHECK(e.on_statusword(0x0218, 2000) == cw::disable_voltage);   // bit 7 low first
    CHECK(e.on_statusword(0x0218, 3000) == cw::fault_reset);       // then high: the edge
    CHECK(e.fault_resets() == 1);
    CHECK(e.on_statusword(0x0218, 4000) == cw::fault_reset);       // held while the drive resets
    CHECK(e.on_statusword(0x0250, 5000) == cw::shutdown);
    CHECK(e.on_statusword(0x0231, 6000) == cw::switch_on);
    CHECK(e.on_statusword(0x0233, 7000) == cw::enable_operation);
    CHECK(e.on_statusword(0x0237, 8000) == cw::enable_operation);
    CHECK(e.reached());
}

TEST_CASE("Enabler retries a stuck transition, then fails")
{
    Enabler e(Enabler::Options{100'000, 2});
    e.set_goal(true, 0);
    e.on_statusword(0x0250, 0);
    CHECK_FALSE(e.check_timeout(100'000));
    CHECK(e.check_timeout(100'001));
    CHECK(e.command() == cw::shutdown);
    CHECK(e.check_timeout(200'002));
    CHECK_FALSE(e.failed());
    CHECK_FALSE(e.check_timeout(300'003));
    CHECK(e.failed());
    CHECK(e.retries() == 2);
}

TEST_CASE("Enabler: a fault that does not clear gets a fresh edge on each retry")
{
    Enabler e(Enabler::Options{100'000, 3});
    e.set_goal(true, 0);
    e.on_statusword(0x0218, 0);
    e.on_statusword(0x0218, 10);
    CHECK(e.command() == cw::fault_reset);
    CHECK(e.check_timeout(100'011));
    CHECK(e.command() == cw::disable_voltage);
    CHECK(e.on_statusword(0x0218, 100'020) == cw::fault_reset);
    CHECK(e.fault_resets() == 2);
}
