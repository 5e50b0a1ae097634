#include "slcan_transport.hpp"

#include <chrono>
#include <thread>

#include "ugv/io/clock.hpp"

namespace ugv::io {

SlcanTransport::SlcanTransport(std::string device, int serial_baud, int bitrate)
    : device_(std::move(device)), serial_baud_(serial_baud), bitrate_(bitrate)
{
}

std::string SlcanTransport::describe() const
{
    return "slcan:" + device_ + "@" + std::to_string(serial_baud_);
}

bool SlcanTransport::open()
{
    pending_.clear();
    if (!port_.open(device_, serial_baud_)) {
        error_ = port_.last_error();
        return false;
    }
    const auto rate = slcan::encode_bitrate(bitrate_);
    if (!rate) {
        error_ = describe() + ": bitrate " + std::to_string(bitrate_) + " is not one slcan can set";
        return false;
    }
    // Close first: an adapter left open from a previous run refuses S<n>. Its answer (BEL
    // when it was already closed) does not matter -- but a late one must not be read as the
    // answer to S<n> (or later as a bus error), nor may an answer to the C of the last
    // close() still waiting in the port: wait a little, then drop whatever came.
    command(slcan::close_command(), 200);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    port_.flush_input();
    decoder_ = slcan::Decoder{};
    if (!command(*rate, 500) || !command(slcan::open_command(), 500)) {
        if (error_.empty()) error_ = describe() + ": the adapter did not accept the set-up";
        port_.close();
        return false;
    }
    return true;
}

void SlcanTransport::close()
{
    if (port_.is_open()) {
        const std::string c = slcan::close_command();
        port_.write(reinterpret_cast<const uint8_t*>(c.data()), c.size());
        port_.drain_output();
    }
    port_.close();
}

bool SlcanTransport::command(const std::string& cmd, int timeout_ms)
{
    error_.clear();
    if (!port_.write(reinterpret_cast<const uint8_t*>(cmd.data()), cmd.size())) {
        error_ = port_.last_error();
        return false;
    }
    const int64_t deadline = monotonic_us() + int64_t{timeout_ms} * 1000;
    while (monotonic_us() < deadline) {
        uint8_t buf[256];
        const ReadResult r = port_.read(buf, sizeof buf, 20);
        if (r.status == ReadResult::Status::closed || r.status == ReadResult::Status::error) {
            error_ = port_.last_error();
            return false;
        }
        for (auto& e : decoder_.feed(buf, r.n)) {
            if (e.kind == slcan::Event::Kind::ok) return true;
            if (e.kind == slcan::Event::Kind::error) {
                error_ = describe() + ": adapter refused '" + cmd.substr(0, cmd.size() - 1) + "'";
                return false;
            }
            if (e.kind == slcan::Event::Kind::frame) {
                CanReceive c;
                c.status = CanReceive::Status::frame;
                c.frame = e.frame;
                c.utime = r.utime;
                pending_.push_back(c);
            }
        }
    }
    error_ = describe() + ": no answer to '" + cmd.substr(0, cmd.size() - 1) + "' (no adapter, or its serial side is not at " +
             std::to_string(serial_baud_) + " baud)";
    return false;
}

bool SlcanTransport::send(const CanFrame& frame)
{
    const std::string s = slcan::encode_frame(frame);
    if (!port_.write(reinterpret_cast<const uint8_t*>(s.data()), s.size())) {
        error_ = port_.last_error();
        return false;
    }
    return true;
}

void SlcanTransport::fill(int timeout_ms)
{
    uint8_t buf[512];
    const ReadResult r = port_.read(buf, sizeof buf, timeout_ms);
    if (r.status == ReadResult::Status::closed || r.status == ReadResult::Status::error) {
        CanReceive c;
        c.status = r.status == ReadResult::Status::closed ? CanReceive::Status::closed : CanReceive::Status::error;
        c.detail = port_.last_error();
        c.utime = r.utime;
        pending_.push_back(c);
        return;
    }
    for (auto& e : decoder_.feed(buf, r.n)) {
        CanReceive c;
        c.utime = r.utime;
        switch (e.kind) {
        case slcan::Event::Kind::frame:
            c.status = CanReceive::Status::frame;
            c.frame = e.frame;
            break;
        case slcan::Event::Kind::error:
            c.status = CanReceive::Status::bus_error;
            c.detail = "adapter error (BEL)";
            break;
        case slcan::Event::Kind::malformed:
            c.status = CanReceive::Status::error;
            c.detail = "malformed slcan line '" + e.text + "'";
            break;
        default:
            continue;  // ok / tx acknowledgements carry nothing for the caller
        }
        pending_.push_back(c);
    }
}

CanReceive SlcanTransport::receive(int timeout_ms)
{
    if (pending_.empty()) {
        if (!port_.is_open()) {
            CanReceive c;
            c.status = CanReceive::Status::closed;
            c.detail = describe() + ": not open";
            return c;
        }
        const int64_t deadline = monotonic_us() + int64_t{timeout_ms} * 1000;
        do {
            const int64_t left_ms = (deadline - monotonic_us()) / 1000;
            fill(static_cast<int>(left_ms > 0 ? left_ms : 0));
        } while (pending_.empty() && monotonic_us() < deadline);
    }
    if (pending_.empty()) return CanReceive{};
    CanReceive c = pending_.front();
    pending_.pop_front();
    return c;
}

}  // namespace ugv::io
