// Silence is not a disconnection: a real receiver's capture (swri gpgga-gprmc-bestpos: 40
// epochs of #BESTPOSA + $GPGGA + $GPRMC, one NovAtel receiver at 20 Hz) written into a
// pseudo-terminal after the line was silent must be decoded whole, every time; and a device
// that is really gone (pty closed, node replaced) is still reopened. The test plays the
// receiver itself on an io::Pty, so it knows exactly which bytes it sent and when.
#include <catch2/catch.hpp>

#include <poll.h>
#include <unistd.h>

#include <fstream>
#include <iterator>

#include "gps_rig.hpp"
#include "ugv/io/pty.hpp"

using namespace ugv::test::gps;
using ugv::test::TempDir;

namespace {

constexpr int kEpochs = 40;

// The capture cut into its 40 epochs (each starts at a #BESTPOSA), and each epoch's GPS time
// read from the #BESTPOSA text (week, seconds): what every published fix must carry.
struct Capture
{
    std::vector<std::string> epochs;
    std::vector<int32_t> gps_ms;
    int32_t week = 0;
};

Capture load_capture()
{
    const std::string path = std::string(UGV_SHARED_DIR) + "/data/real/swri-novatel_gps_driver/gpgga-gprmc-bestpos.udp-payload.bin";
    std::ifstream in(path, std::ios::binary);
    REQUIRE(in);
    const std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    Capture c;
    std::size_t at = data.find("#BESTPOSA");
    REQUIRE(at == 0);
    while (at != std::string::npos) {
        const std::size_t next = data.find("#BESTPOSA", at + 1);
        c.epochs.push_back(data.substr(at, next == std::string::npos ? std::string::npos : next - at));
        // #BESTPOSA,ICOM1,0,80.0,FINESTEERING,1957,339804.750,...
        std::vector<std::string> f;
        std::size_t p = at;
        for (int i = 0; i < 7; ++i) {
            const std::size_t q = data.find(',', p);
            f.push_back(data.substr(p, q - p));
            p = q + 1;
        }
        c.week = std::stoi(f[5]);
        c.gps_ms.push_back(static_cast<int32_t>(std::llround(std::stod(f[6]) * 1000.0)));
        at = next;
    }
    REQUIRE(c.epochs.size() == kEpochs);
    return c;
}

// Writes all of s into the pty's master (non-blocking), waiting for room when it is full.
void write_all(int fd, const std::string& s)
{
    std::size_t done = 0;
    while (done < s.size()) {
        const ssize_t n = ::write(fd, s.data() + done, s.size() - done);
        if (n > 0) {
            done += static_cast<std::size_t>(n);
            continue;
        }
        REQUIRE((n < 0 && (errno == EAGAIN || errno == EINTR)));
        pollfd p{fd, POLLOUT, 0};
        ::poll(&p, 1, 100);
    }
}

// The capture, one epoch every epoch_s, pumping the bus meanwhile.
void send_capture(Listener& l, int master_fd, const Capture& c, double epoch_s)
{
    for (const auto& e : c.epochs) {
        write_all(master_fd, e);
        l.wait([] { return false; }, epoch_s);
    }
}

// Fixes [from, from + 40) are the capture's 40 epochs, in order, from the #BESTPOSA logs.
void check_round(Listener& l, const Capture& c, std::size_t from)
{
    std::lock_guard<std::mutex> g(l.t.m);
    REQUIRE(l.t.fixes.size() >= from + kEpochs);
    for (int i = 0; i < kEpochs; ++i) {
        const auto& f = l.t.fixes[from + static_cast<std::size_t>(i)];
        INFO("fix " << from + static_cast<std::size_t>(i));
        CHECK(f.gps_week == c.week);
        CHECK(f.gps_ms == c.gps_ms[static_cast<std::size_t>(i)]);
        CHECK(f.source == ugv::gps_fix_t::SOURCE_NOVATEL_ASCII);
        CHECK_THAT(f.latitude, Catch::Matchers::WithinAbs(29.4439, 1e-3));
        CHECK_THAT(f.longitude, Catch::Matchers::WithinAbs(-98.6147, 1e-3));
    }
}

// silence_timeout_s is the daemon's own "degraded after" key (the receiver's 1.25 s by
// default with 0.25 s logs): at 0.25 s a silence of 0.75 s crosses it three times. Empty:
// the default.
std::unique_ptr<ugv::test::Process> start_gps(const TempDir& dir, const std::string& device, int port,
                                              const std::string& silence_timeout_s = "0.25")
{
    ugv::test::write_file(dir / "gps.toml", "device = \"" + device + "\"\nmode = \"passive\"\nprotocol = \"auto\"\n" +
                                                (silence_timeout_s.empty() ? "" : "silence_timeout_s = " + silence_timeout_s + "\n"));
    return std::make_unique<ugv::test::Process>(std::vector<std::string>{ugv::test::bin("ugv-gps"), "--config", dir / "gps.toml",
                                                              "--lcm-url", ugv::test::lcm_url(port)},
                                     dir / "gps.out", dir / "gps.err");
}

}  // namespace

TEST_CASE("ugv-gps: a real capture after silence is decoded whole, 20 times of 20; silence never reopens")
{
    // The reported failure (9, 15, 38 or 40 of 40 fixes after 5 s of silence) came from the
    // daemon reopening the port each silence_timeout_s while the receiver was quiet, and
    // flushing what arrived around a reopen. What matters is silence longer than that
    // timeout, not its length in seconds: here the timeout is 0.25 s and each silence 0.75 s
    // (three timeouts, as 5 s was four of the default 1.25 s), so one daemon run takes 20
    // rounds in ~30 s. The capture goes at 80 epochs/s (its own order and framing, 4x its
    // 20 Hz pace), each epoch in one write, as a serial adapter delivers a burst.
    const Capture c = load_capture();
    TempDir dir;
    ugv::io::Pty receiver(dir / "gps");
    Listener l(7880);
    auto gps = start_gps(dir, receiver.path(), 7880);
    INFO("--- ugv-gps stderr:\n" << gps->err());
    // The daemon has the port open and has seen the line silent once: nothing written from
    // here on can be flushed by its open().
    REQUIRE(l.wait([&] { return l.t.counter("silences") >= 1; }, 20.0));

    constexpr int kRounds = 20;
    int whole = 0;
    for (int round = 0; round < kRounds; ++round) {
        const std::size_t before = l.t.nfix();
        REQUIRE(before == static_cast<std::size_t>(round) * kEpochs);  // nothing published during the silence
        send_capture(l, receiver.master_fd(), c, 1.0 / 80);
        // A missing fix never comes: wait well past the last epoch's arrival, then count.
        l.wait([&] { return l.t.nfix() >= before + kEpochs; }, 5.0);
        l.wait([] { return false; }, 0.75);  // the silence before the next round
        const std::size_t got = l.t.nfix() - before;
        INFO("round " << round << ": " << got << " of " << kEpochs << " fixes");
        CHECK(got == kEpochs);
        if (got == kEpochs) {
            ++whole;
            check_round(l, c, before);
        }
        if (got != kEpochs) break;
    }
    CHECK(whole == kRounds);
    // One silence before each round (and the last one after), DEGRADED each time; never a
    // reopen; RUNNING while the capture flowed.
    REQUIRE(l.wait([&] { return l.t.counter("silences") >= kRounds + 1; }, 5.0));
    CHECK(l.t.counter("reconnects") == 0);
    CHECK(l.t.counter("open_failures") == 0);
    CHECK(l.t.saw_state(ugv::daemon_status_t::STATE_DEGRADED));
    CHECK(l.t.saw_state(ugv::daemon_status_t::STATE_RUNNING));
    gps->signal(SIGTERM);
    CHECK(gps->wait_exit(5.0) == 0);
}

TEST_CASE("ugv-gps: on its defaults, a capture after 5 s of silence is decoded whole, at the receiver's pace")
{
    // The reported condition itself, once: the default silence timeout, 5 s of silence, the
    // capture at its own 20 Hz. The 20 repetitions are the case above.
    const Capture c = load_capture();
    TempDir dir;
    ugv::io::Pty receiver(dir / "gps");
    Listener l(7883);
    auto gps = start_gps(dir, receiver.path(), 7883, "");
    INFO("--- ugv-gps stderr:\n" << gps->err());
    REQUIRE(l.wait([&] { return l.t.counter("silences") >= 1; }, 20.0));
    l.wait([] { return false; }, 5.0);
    REQUIRE(l.t.nfix() == 0);
    send_capture(l, receiver.master_fd(), c, 1.0 / 20);
    l.wait([&] { return l.t.nfix() >= kEpochs; }, 5.0);
    CHECK(l.t.nfix() == kEpochs);
    check_round(l, c, 0);
    CHECK(l.t.counter("reconnects") == 0);
    gps->signal(SIGTERM);
    CHECK(gps->wait_exit(5.0) == 0);
}

TEST_CASE("ugv-gps: a device that is gone is reopened, and the capture is decoded whole from the new one")
{
    const Capture c = load_capture();
    TempDir dir;
    const std::string link = dir / "gps";
    auto old_receiver = std::make_unique<ugv::io::Pty>(link);
    std::unique_ptr<ugv::io::Pty> new_receiver;
    int port = 0;
    std::string how;

    SECTION("the pty closed (unplugged: the daemon's fd hangs up)")
    {
        port = 7881;
        how = "closed";
    }
    SECTION("the node replaced by another pty while the old one stays open and silent (no hang-up)")
    {
        port = 7882;
        how = "replaced";
    }
    Listener l(port);
    auto gps = start_gps(dir, link, port);
    INFO("--- ugv-gps stderr:\n" << gps->err());
    REQUIRE(l.wait([&] { return l.t.counter("silences") >= 1; }, 20.0));
    send_capture(l, old_receiver->master_fd(), c, 1.0 / 80);
    REQUIRE(l.wait([&] { return l.t.nfix() >= kEpochs; }, 5.0));
    CHECK(l.t.counter("reconnects") == 0);

    if (how == "closed") {
        old_receiver->close();
        l.wait([] { return false; }, 0.5);  // gone for a while: the reopen fails meanwhile
        new_receiver = std::make_unique<ugv::io::Pty>(link);
    } else {
        new_receiver = std::make_unique<ugv::io::Pty>(link);  // the link now names another tty
    }
    REQUIRE(l.wait([&] { return l.t.counter("reconnects") >= 1; }, 10.0));
    if (how == "replaced") {
        // The old device is no longer read: what it sends now is lost with it.
        send_capture(l, old_receiver->master_fd(), c, 1.0 / 200);
        l.wait([] { return false; }, 0.5);
        CHECK(l.t.nfix() == kEpochs);
    }
    send_capture(l, new_receiver->master_fd(), c, 1.0 / 80);
    REQUIRE(l.wait([&] { return l.t.nfix() >= 2 * kEpochs; }, 5.0));
    l.wait([] { return false; }, 0.5);
    CHECK(l.t.nfix() == 2 * kEpochs);
    check_round(l, c, kEpochs);
    CHECK(l.t.counter("reconnects") == 1);
    CHECK(l.t.saw_state(ugv::daemon_status_t::STATE_DEGRADED));
    gps->signal(SIGTERM);
    CHECK(gps->wait_exit(5.0) == 0);
}
