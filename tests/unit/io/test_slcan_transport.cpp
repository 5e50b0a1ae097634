// slcan over a real pseudo-terminal, against a test peer that plays the USB adapter.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <atomic>
#include <thread>

#include "ugv/io/can_transport.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/pty.hpp"
#include "ugv/io/slcan_codec.hpp"
#include "ugv_test/process.hpp"

using namespace ugv::io;

namespace {

// A minimal adapter: answers S<n>/O/C with CR (or BEL when told to refuse), and echoes every
// transmitted frame back with the id + 0x80 (as a CANopen node answers 0x600+n with 0x580+n).
class AdapterPeer
{
public:
    explicit AdapterPeer(Pty& pty, bool refuse_open = false) : pty_(pty), refuse_open_(refuse_open)
    {
        thread_ = std::thread([this] { loop(); });
    }
    ~AdapterPeer()
    {
        stop_ = true;
        thread_.join();
    }
    std::string commands() const { return seen_; }
    int slave_baud_at_open() const { return baud_at_open_; }

private:
    void loop()
    {
        std::string line;
        while (!stop_) {
            char c;
            const ssize_t n = ::read(pty_.master_fd(), &c, 1);
            if (n <= 0) {
                usleep(500);
                continue;
            }
            if (c != '\r') {
                line += c;
                continue;
            }
            seen_ += line + ";";
            std::string reply = "\r";
            if (line == "O") {
                baud_at_open_ = pty_.slave_baud();
                if (refuse_open_) reply = "\a";
            } else if (!line.empty() && line[0] == 't') {
                auto e = slcan::decode_line(line);
                e.frame.id += 0x80;
                reply = "z\r" + slcan::encode_frame(e.frame);
            }
            [[maybe_unused]] auto w = ::write(pty_.master_fd(), reply.data(), reply.size());
            line.clear();
        }
    }
    Pty& pty_;
    bool refuse_open_;
    std::atomic<bool> stop_{false};
    std::atomic<int> baud_at_open_{0};
    std::string seen_;
    std::thread thread_;
};

}  // namespace

TEST_CASE("slcan transport sets the bitrate, opens the channel and round-trips frames")
{
    ugv::test::TempDir dir;
    Pty pty(dir / "ttyACM0");
    AdapterPeer peer(pty);
    auto t = make_can_transport("slcan:" + pty.path() + "@921600", 500000);
    CHECK(t->describe() == "slcan:" + pty.path() + "@921600");
    REQUIRE(t->open());
    CHECK(peer.slave_baud_at_open() == 921600);
    CHECK(peer.commands() == "C;S6;O;");

    CanFrame sdo;
    sdo.id = 0x605;
    sdo.dlc = 8;
    sdo.data = {0x40, 0x41, 0x60, 0x00, 0, 0, 0, 0};
    REQUIRE(t->send(sdo));
    const int64_t before = now_utime();
    const CanReceive r = t->receive(2000);
    REQUIRE(r.status == CanReceive::Status::frame);
    CHECK(r.frame.id == 0x685);
    CHECK(r.frame.data == sdo.data);
    CHECK(r.utime >= before - 1000);
    CHECK(t->receive(50).status == CanReceive::Status::timeout);
}

TEST_CASE("slcan transport says why when the adapter refuses to open")
{
    Pty pty;
    AdapterPeer peer(pty, true);
    auto t = make_can_transport("slcan:" + pty.path(), 250000);
    CHECK_FALSE(t->open());
    CHECK(t->last_error() == "slcan:" + pty.path() + "@115200: adapter refused 'O'");
}

TEST_CASE("slcan transport reports an unplugged adapter as closed")
{
    ugv::test::TempDir dir;
    auto pty = std::make_unique<Pty>(dir / "ttyACM0");
    auto t = make_can_transport("slcan:" + pty->path(), 500000);
    {
        AdapterPeer peer(*pty);
        REQUIRE(t->open());
    }
    pty->close();
    CanReceive r;
    for (int k = 0; k < 20 && r.status != CanReceive::Status::closed; ++k) r = t->receive(50);
    CHECK(r.status == CanReceive::Status::closed);
}

TEST_CASE("CAN transport specs are checked at start-up with a one-line reason")
{
    CHECK_THROWS_WITH(make_can_transport("can0", 500000), "'can0' is not socketcan:IFACE or slcan:DEVICE[@BAUD]");
    CHECK_THROWS_WITH(make_can_transport("pcan:usb0", 500000), "unknown CAN transport 'pcan' (socketcan or slcan)");
    CHECK_THROWS_WITH(make_can_transport("slcan:/dev/ttyACM0@fast", 500000), "'fast' is not a serial baud rate");
    CHECK(make_can_transport("socketcan:can0", 500000)->describe() == "socketcan:can0");
}

TEST_CASE("slcan transport refuses a CAN bitrate the protocol cannot set")
{
    Pty pty;
    AdapterPeer peer(pty);
    auto t = make_can_transport("slcan:" + pty.path(), 333333);
    CHECK_FALSE(t->open());
    CHECK(t->last_error().find("bitrate 333333 is not one slcan can set") != std::string::npos);
}
