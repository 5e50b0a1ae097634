#include <catch2/catch.hpp>

#include <chrono>
#include <unistd.h>

#include "ugv/io/clock.hpp"
#include "ugv/io/pty.hpp"
#include "ugv/io/serial_port.hpp"
#include "ugv_test/process.hpp"

using ugv::io::Pty;
using ugv::io::ReadResult;
using ugv::io::SerialPort;

namespace {
std::string read_master(int fd, std::size_t want, int timeout_ms = 2000)
{
    std::string got;
    const int64_t end = ugv::io::monotonic_us() + timeout_ms * 1000;
    while (got.size() < want && ugv::io::monotonic_us() < end) {
        char buf[256];
        const ssize_t n = ::read(fd, buf, sizeof buf);
        if (n > 0) got.append(buf, static_cast<std::size_t>(n));
        else usleep(1000);
    }
    return got;
}
}  // namespace

TEST_CASE("SerialPort opens a pty raw and the other side sees the baud it set, 500000 included")
{
    ugv::test::TempDir dir;
    Pty pty(dir / "tty");
    SerialPort port;
    REQUIRE(port.open(pty.path(), 9600));
    CHECK(pty.slave_baud() == 9600);
    for (const int baud : {19200, 38400, 115200, 500000, 921600}) {
        REQUIRE(port.set_baud(baud));
        CHECK(port.baud() == baud);
        CHECK(pty.slave_baud() == baud);
    }
}

TEST_CASE("SerialPort moves bytes both ways unchanged, with a receive time stamp")
{
    Pty pty;
    SerialPort port;
    REQUIRE(port.open(pty.path(), 500000));
    // Every byte value, including the ones a cooked tty would translate (CR, LF, ^C, ^S, DEL).
    std::string all;
    for (int b = 0; b < 256; ++b) all += static_cast<char>(b);
    REQUIRE(port.write(reinterpret_cast<const uint8_t*>(all.data()), all.size()));
    CHECK(read_master(pty.master_fd(), all.size()) == all);

    REQUIRE(::write(pty.master_fd(), all.data(), all.size()) == 256);
    std::string got;
    int64_t first_stamp = 0;
    const int64_t before = ugv::io::now_utime();
    while (got.size() < all.size()) {
        uint8_t buf[64];
        const ReadResult r = port.read(buf, sizeof buf, 1000);
        REQUIRE(r.status == ReadResult::Status::data);
        if (first_stamp == 0) first_stamp = r.utime;
        got.append(reinterpret_cast<char*>(buf), r.n);
    }
    CHECK(got == all);
    CHECK(first_stamp >= before);
    CHECK(first_stamp <= ugv::io::now_utime());
}

TEST_CASE("SerialPort read times out when nothing comes")
{
    Pty pty;
    SerialPort port;
    REQUIRE(port.open(pty.path(), 38400));
    uint8_t buf[8];
    const int64_t t0 = ugv::io::monotonic_us();
    const ReadResult r = port.read(buf, sizeof buf, 50);
    CHECK(r.status == ReadResult::Status::timeout);
    CHECK(r.n == 0);
    CHECK(ugv::io::monotonic_us() - t0 >= 45'000);
}

TEST_CASE("SerialPort inter-byte spacing still delivers every byte")
{
    Pty pty;
    SerialPort port;
    REQUIRE(port.open(pty.path(), 9600));
    port.set_inter_byte_spacing(std::chrono::microseconds(200));
    const std::string msg = "\x02\x80\x02\x00\x20\x24\x34\x08";
    REQUIRE(port.write(reinterpret_cast<const uint8_t*>(msg.data()), msg.size()));
    CHECK(read_master(pty.master_fd(), msg.size()) == msg);
}

TEST_CASE("SerialPort reports an unplugged device as closed and reopens when it is back")
{
    ugv::test::TempDir dir;
    const std::string link = dir / "gps";
    auto pty = std::make_unique<Pty>(link);
    SerialPort port;
    REQUIRE(port.open(link, 115200));
    pty->close();  // unplugged
    uint8_t buf[8];
    ReadResult r;
    for (int k = 0; k < 10 && r.status != ReadResult::Status::closed; ++k) r = port.read(buf, sizeof buf, 100);
    CHECK(r.status == ReadResult::Status::closed);
    CHECK_FALSE(port.last_error().empty());
    CHECK_FALSE(port.reopen());  // nothing there yet
    CHECK(port.last_error().find(link) == 0);
    pty = std::make_unique<Pty>(link);  // plugged back in (a new tty behind the same name)
    INFO(port.last_error());
    REQUIRE(port.reopen());
    CHECK(port.baud() == 115200);
    CHECK(pty->slave_baud() == 115200);
    REQUIRE(::write(pty->master_fd(), "ok", 2) == 2);
    r = port.read(buf, sizeof buf, 1000);
    REQUIRE(r.status == ReadResult::Status::data);
    CHECK(std::string(reinterpret_cast<char*>(buf), r.n) == "ok");
}

TEST_CASE("SerialPort: a quiet device is not gone, however long it is quiet")
{
    ugv::test::TempDir dir;
    Pty pty(dir / "gps");
    SerialPort port;
    REQUIRE(port.open(pty.path(), 9600));
    uint8_t buf[8];
    // Three node checks' worth of silence: every read a timeout, none `closed`.
    const int64_t end = ugv::io::monotonic_us() + 3 * std::chrono::microseconds(SerialPort::kNodeCheckPeriod).count();
    int reads = 0;
    while (ugv::io::monotonic_us() < end) {
        const ReadResult r = port.read(buf, sizeof buf, 50);
        REQUIRE(r.status == ReadResult::Status::timeout);
        ++reads;
    }
    CHECK(reads >= 10);
    CHECK(port.node_present());
    REQUIRE(::write(pty.master_fd(), "ok", 2) == 2);
    const ReadResult r = port.read(buf, sizeof buf, 1000);
    REQUIRE(r.status == ReadResult::Status::data);
    CHECK(std::string(reinterpret_cast<char*>(buf), r.n) == "ok");
}

TEST_CASE("SerialPort: a node that vanished or now names another device is gone, though the fd never hung up")
{
    ugv::test::TempDir dir;
    const std::string link = dir / "gps";
    auto old_pty = std::make_unique<Pty>(link);
    SerialPort port;
    REQUIRE(port.open(link, 9600));
    CHECK(port.node_present());
    uint8_t buf[8];
    const auto read_until_closed = [&] {
        ReadResult r;
        for (int k = 0; k < 40 && r.status != ReadResult::Status::closed; ++k) r = port.read(buf, sizeof buf, 50);
        return r.status;
    };

    SECTION("replaced: the link now points at another pty; the old one stays open and silent")
    {
        Pty new_pty(link);
        CHECK_FALSE(port.node_present());
        CHECK(port.last_error() == link + ": device node replaced by another device");
        CHECK(read_until_closed() == ReadResult::Status::closed);
        REQUIRE(port.reopen());
        REQUIRE(::write(new_pty.master_fd(), "new", 3) == 3);
        const ReadResult r = port.read(buf, sizeof buf, 1000);
        REQUIRE(r.status == ReadResult::Status::data);
        CHECK(std::string(reinterpret_cast<char*>(buf), r.n) == "new");
        CHECK(port.node_present());
    }
    SECTION("vanished: the link removed; the old pty stays open and silent")
    {
        REQUIRE(::unlink(link.c_str()) == 0);
        CHECK_FALSE(port.node_present());
        CHECK(port.last_error() == link + ": device node vanished");
        CHECK(read_until_closed() == ReadResult::Status::closed);
        CHECK_FALSE(port.reopen());
    }
}

TEST_CASE("SerialPort refuses what is not a serial port, in one line naming the path")
{
    SerialPort port;
    CHECK_FALSE(port.open("/nonexistent/ttyUSB9", 9600));
    CHECK(port.last_error() == "/nonexistent/ttyUSB9: cannot open: No such file or directory");
    CHECK_FALSE(port.open("/dev/null", 9600));
    CHECK(port.last_error().rfind("/dev/null: not a serial port", 0) == 0);
}

TEST_CASE("transmission time counts 10 bits per byte")
{
    CHECK(ugv::io::transmission_time_s(732, 500000) == Approx(0.01464));
    CHECK(ugv::io::transmission_time_s(1, 9600) == Approx(1.0 / 960.0));
}
