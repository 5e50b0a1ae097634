// SocketCAN needs AF_CAN in the kernel and a CAN interface (vcan0 on a bench PC:
// `modprobe vcan; ip link add vcan0 type vcan; ip link set vcan0 up`). Where either is
// missing, the whole executable exits 77 before any test, and CTest reports it as skipped.
#include <catch2/catch.hpp>

#include <net/if.h>

#include <cstdio>
#include <cstdlib>

#include "ugv/io/can_transport.hpp"

namespace {

std::string can_iface()
{
    const char* e = std::getenv("UGV_TEST_CAN_IFACE");
    return e && *e ? e : "vcan0";
}

const bool g_skip = [] {
    if (!ugv::io::socketcan_available()) {
        std::printf("SKIPPED test_socketcan_transport: this kernel refuses AF_CAN sockets (no SocketCAN)\n");
        std::exit(77);
    }
    if (if_nametoindex(can_iface().c_str()) == 0) {
        std::printf("SKIPPED test_socketcan_transport: no CAN interface %s\n", can_iface().c_str());
        std::exit(77);
    }
    return false;
}();

}  // namespace

TEST_CASE("SocketCAN: two sockets on one interface see each other's frames")
{
    auto a = ugv::io::make_can_transport("socketcan:" + can_iface(), 500000);
    auto b = ugv::io::make_can_transport("socketcan:" + can_iface(), 500000);
    REQUIRE(a->open());
    REQUIRE(b->open());
    ugv::io::CanFrame f;
    f.id = 0x181;
    f.dlc = 4;
    f.data = {1, 2, 3, 4, 0, 0, 0, 0};
    REQUIRE(a->send(f));
    const auto r = b->receive(1000);
    REQUIRE(r.status == ugv::io::CanReceive::Status::frame);
    CHECK(r.frame == f);
    CHECK(r.utime > 0);
}

TEST_CASE("SocketCAN: a missing interface is refused with a one-line reason")
{
    auto t = ugv::io::make_can_transport("socketcan:nosuchcan9", 500000);
    CHECK_FALSE(t->open());
    CHECK(t->last_error().rfind("socketcan:nosuchcan9: no such interface", 0) == 0);
}
