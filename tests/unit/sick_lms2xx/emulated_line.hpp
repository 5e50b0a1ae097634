// A ugv::io::ByteStream joined to the LMS emulator core in simulated time: reads advance a
// virtual clock, so a session's timeouts, settle times and back-offs cost no real time.
#pragma once

#include <algorithm>
#include <cstring>
#include <deque>
#include <memory>
#include <string>

#include "lms_emulator.hpp"
#include "ugv/io/byte_stream.hpp"

namespace ugv::test {

class EmulatedLine final : public io::ByteStream
{
public:
    explicit EmulatedLine(sim::lms::DeviceOptions options) : options_(options), device_(std::make_unique<sim::lms::LmsDevice>(options)) {}

    int64_t now_us = 1'000'000;                       // monotonic, virtual
    static constexpr int64_t kEpochUs = 1'700'000'000'000'000;  // utime = epoch + now_us
    bool unplugged = false;
    std::size_t max_chunk = 4096;                     // longest read, to exercise splits

    sim::lms::LmsDevice& device() { return *device_; }
    // Unplug: reads report closed until replug().
    void unplug() { unplugged = true; }
    // A fresh device (as after a power cycle) on the same line.
    void replug()
    {
        device_ = std::make_unique<sim::lms::LmsDevice>(options_);
        pending_.clear();
        unplugged = false;
    }

    io::ReadResult read(uint8_t* buf, std::size_t cap, int timeout_ms) override
    {
        io::ReadResult r;
        if (unplugged) {
            error_ = "unplugged";
            r.status = io::ReadResult::Status::closed;
            return r;
        }
        const int64_t deadline = now_us + int64_t{timeout_ms} * 1000;
        while (pending_.empty()) {
            const int64_t next = std::min(deadline, device_->next_event_us());
            if (next > now_us) now_us = next;
            std::vector<uint8_t> out;
            device_->tick(now_us, baud_, out);
            pending_.insert(pending_.end(), out.begin(), out.end());
            if (pending_.empty() && now_us >= deadline) {
                r.status = io::ReadResult::Status::timeout;
                return r;
            }
        }
        const std::size_t n = std::min({cap, pending_.size(), max_chunk});
        std::copy_n(pending_.begin(), n, buf);
        pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(n));
        r.status = io::ReadResult::Status::data;
        r.n = n;
        r.utime = kEpochUs + now_us;
        return r;
    }
    bool write(const uint8_t* data, std::size_t n) override
    {
        if (unplugged) return false;
        written.insert(written.end(), data, data + n);
        std::vector<uint8_t> out;
        device_->receive(data, n, baud_, now_us, out);
        pending_.insert(pending_.end(), out.begin(), out.end());
        return true;
    }
    bool set_baud(int baud) override
    {
        baud_ = baud;
        bauds_set.push_back(baud);
        return true;
    }
    int baud() const override { return baud_; }
    void flush_input() override { pending_.clear(); }
    const std::string& last_error() const override { return error_; }

    std::vector<uint8_t> written;
    std::vector<int> bauds_set;

private:
    sim::lms::DeviceOptions options_;
    std::unique_ptr<sim::lms::LmsDevice> device_;
    std::deque<uint8_t> pending_;
    int baud_ = 9600;
    std::string error_;
};

}  // namespace ugv::test
