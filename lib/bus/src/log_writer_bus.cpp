// Publishing into an LCM log file (the processing daemons' --out), in the format lcm-logger
// writes, so lcm-logplayer, ugv-dump and lcm-spy read it.
#include <lcm/eventlog.h>

#include "ugv/bus/bus.hpp"

namespace ugv::bus {
namespace {

class LogWriterBus final : public Bus
{
public:
    LogWriterBus(std::string path, std::function<int64_t()> clock) : path_(std::move(path)), clock_(std::move(clock))
    {
        log_ = lcm_eventlog_create(path_.c_str(), "w");
        if (!log_) throw BusError(path_ + ": cannot create the LCM log");
    }
    ~LogWriterBus() override { lcm_eventlog_destroy(log_); }

    bool publish(const std::string& channel, const void* data, std::size_t size) override
    {
        lcm_eventlog_event_t ev{};
        ev.eventnum = next_event_++;
        ev.timestamp = clock_();
        ev.channellen = static_cast<int32_t>(channel.size());
        ev.datalen = static_cast<int32_t>(size);
        ev.channel = const_cast<char*>(channel.c_str());
        ev.data = const_cast<void*>(data);
        if (lcm_eventlog_write_event(log_, &ev) != 0) {
            ++counters_.publish_failures;
            return false;
        }
        return true;
    }

    void subscribe(const std::string&, RawHandler) override {}
    HandleResult handle(int) override { return HandleResult::end; }
    int64_t now_utime() const override { return clock_(); }
    std::string describe() const override { return "log " + path_ + " (writing)"; }

private:
    std::string path_;
    std::function<int64_t()> clock_;
    lcm_eventlog_t* log_ = nullptr;
    int64_t next_event_ = 0;
};

}  // namespace

std::unique_ptr<Bus> open_log_writer(const std::string& path, std::function<int64_t()> clock)
{
    return std::make_unique<LogWriterBus>(path, std::move(clock));
}

}  // namespace ugv::bus
