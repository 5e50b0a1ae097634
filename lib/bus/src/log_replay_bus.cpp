// Replay of an LCM log: each handle() dispatches the next event to every subscription whose
// regex matches its channel, in file order, as fast as the caller asks. Deterministic: the
// same log always gives the same calls with the same recv_utime (the log's time stamp).
#include <lcm/eventlog.h>

#include <regex>
#include <vector>

#include "handler_guard.hpp"
#include "ugv/bus/bus.hpp"

namespace ugv::bus {
namespace {

class LogReplayBus final : public Bus
{
public:
    explicit LogReplayBus(std::string path) : path_(std::move(path))
    {
        log_ = lcm_eventlog_create(path_.c_str(), "r");
        if (!log_) throw BusError(path_ + ": cannot open as an LCM log");
    }
    ~LogReplayBus() override { lcm_eventlog_destroy(log_); }

    bool publish(const std::string&, const void*, std::size_t) override
    {
        ++counters_.publish_failures;  // a log being read is not written
        return false;
    }

    void subscribe(const std::string& channel_regex, RawHandler handler) override
    {
        subs_.push_back(Sub{std::regex(channel_regex), std::move(handler)});
    }

    HandleResult handle(int) override
    {
        lcm_eventlog_event_t* ev = lcm_eventlog_read_next_event(log_);
        if (!ev) return HandleResult::end;
        now_ = ev->timestamp;
        const std::string channel(ev->channel, static_cast<std::size_t>(ev->channellen));
        bool any = false;
        for (auto& s : subs_) {
            if (!std::regex_match(channel, s.re)) continue;
            any = true;
            detail::call_guarded(s.handler, counters_, channel, static_cast<const uint8_t*>(ev->data),
                                 static_cast<std::size_t>(ev->datalen), ev->timestamp);
        }
        if (any) ++counters_.received;
        lcm_eventlog_free_event(ev);
        return HandleResult::handled;
    }

    int64_t now_utime() const override { return now_; }
    std::string describe() const override { return "log " + path_; }

private:
    struct Sub
    {
        std::regex re;
        RawHandler handler;
    };
    std::string path_;
    lcm_eventlog_t* log_ = nullptr;
    std::vector<Sub> subs_;
    int64_t now_ = 0;
};

}  // namespace

std::unique_ptr<Bus> open_log_replay(const std::string& path) { return std::make_unique<LogReplayBus>(path); }

}  // namespace ugv::bus
