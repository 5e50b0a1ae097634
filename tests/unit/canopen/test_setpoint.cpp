#include <catch2/catch.hpp>

#include "ugv/canopen/setpoint.hpp"

using namespace ugv::canopen::cia402;

TEST_CASE("Set-point handshake: bit 4 up, wait for bit 12, bit 4 down, wait for bit 12 to fall")
{
    SetpointHandshake h(100'000);
    h.reset(0);
    CHECK_FALSE(h.poll(0));
    h.request(5000, 800);
    CHECK(h.poll(1000));
    CHECK(h.new_setpoint_bit());
    CHECK(h.target() == 5000);
    CHECK(h.velocity() == 800u);
    CHECK_FALSE(h.on_statusword(0x0237, 2000));  // no acknowledge yet
    h.request(6000, 900);                          // arrives during the handshake: queued
    CHECK(h.on_statusword(0x1237, 3000));          // acknowledged: lower bit 4
    CHECK_FALSE(h.new_setpoint_bit());
    CHECK(h.target() == 5000);
    CHECK(h.busy());
    CHECK(h.on_statusword(0x0237, 4000));  // bit 12 fell: the queued one goes at once
    CHECK(h.new_setpoint_bit());
    CHECK(h.target() == 6000);
    CHECK(h.acknowledged() == 1);
}

TEST_CASE("Set-point handshake: the newest queued request wins")
{
    SetpointHandshake h;
    h.reset(0);
    h.request(1, 1);
    h.request(2, 2);
    h.request(3, 3);
    CHECK(h.poll(0));
    CHECK(h.target() == 3);
}

TEST_CASE("Set-point handshake: no acknowledge -> timeout, bit 4 lowered, the target is sent again")
{
    SetpointHandshake h(100'000);
    h.reset(0);
    h.request(700, 10);
    CHECK(h.poll(0));
    CHECK_FALSE(h.poll(100'000));
    CHECK(h.poll(100'001));  // timed out: bit 4 low
    CHECK_FALSE(h.new_setpoint_bit());
    CHECK(h.timeouts() == 1);
    CHECK(h.poll(100'002));  // and raised again for the same target
    CHECK(h.new_setpoint_bit());
    CHECK(h.target() == 700);
}
