#include <catch2/catch.hpp>

#include "frame_helpers.hpp"
#include "ugv/canopen/nmt.hpp"

using namespace ugv::canopen;
using canopen_test::frame;
using canopen_test::text;

TEST_CASE("NMT commands are [cmd, node] on COB-ID 0")
{
    CHECK(text(encode_nmt(NmtCommand::start, 2)) == "000#0102");
    CHECK(text(encode_nmt(NmtCommand::stop, 2)) == "000#0202");
    CHECK(text(encode_nmt(NmtCommand::enter_pre_operational, 0)) == "000#8000");
    CHECK(text(encode_nmt(NmtCommand::reset_node, 5)) == "000#8105");
    CHECK(text(encode_nmt(NmtCommand::reset_communication, 127)) == "000#827F");
}

TEST_CASE("NMT decoding: addressed to this node or to all")
{
    CHECK(decode_nmt(frame("000#0102"), 2) == NmtCommand::start);
    CHECK(decode_nmt(frame("000#8200"), 2) == NmtCommand::reset_communication);
    CHECK_FALSE(decode_nmt(frame("000#0103"), 2).has_value());
    CHECK_FALSE(decode_nmt(frame("000#0702"), 2).has_value());
}

TEST_CASE("Heartbeat states on 0x700 + node")
{
    CHECK(text(encode_heartbeat(2, NmtState::operational)) == "702#05");
    CHECK(decode_heartbeat(frame("702#00"), 2) == NmtState::boot_up);
    CHECK(decode_heartbeat(frame("702#04"), 2) == NmtState::stopped);
    CHECK(decode_heartbeat(frame("702#05"), 2) == NmtState::operational);
    CHECK(decode_heartbeat(frame("702#7F"), 2) == NmtState::pre_operational);
    CHECK_FALSE(decode_heartbeat(frame("703#05"), 2).has_value());
    CHECK_FALSE(decode_heartbeat(frame("702#33"), 2).has_value());
}

TEST_CASE("Heartbeat consumer declares the node lost after 3 missed beats, once")
{
    HeartbeatConsumer hb(2, 100'000);
    hb.reset(0);
    CHECK(hb.on_frame(frame("702#05"), 100'000));
    CHECK(hb.last_state() == NmtState::operational);
    CHECK_FALSE(hb.on_frame(frame("703#05"), 150'000));  // another node's beat
    CHECK_FALSE(hb.check_lost(400'000));                 // exactly 3 periods: not yet
    CHECK(hb.check_lost(400'001));
    CHECK_FALSE(hb.alive());
    CHECK_FALSE(hb.check_lost(900'000));  // reported once
    hb.on_frame(frame("702#05"), 1'000'000);
    CHECK(hb.alive());
    CHECK_FALSE(hb.check_lost(1'250'000));
    CHECK(hb.check_lost(1'300'001));
}
