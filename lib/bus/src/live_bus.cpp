// The live bus. Publishing goes through LCM's C API (lcm_t) for any URL. Receiving:
//   - udpm:// URLs: our own socket on the caller's thread (udpm_receiver.hpp says why), the
//     same wire format and the same whole-name POSIX regex matching as liblcm;
//   - any other URL (memq:// in tests): liblcm's own subscription, whose C callback takes a
//     user pointer, so handlers can be any std::function without LCM 1.4's lambda support.
#include <lcm/lcm.h>
#include <poll.h>
#include <regex.h>

#include <cerrno>

#include <list>
#include <memory>
#include <optional>
#include <unordered_map>

#include "handler_guard.hpp"
#include "ugv/bus/udpm_receiver.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/bus/bus.hpp"

namespace ugv::bus {
namespace {

// A subscription's channel pattern, matched against the whole name as liblcm does.
class ChannelPattern
{
public:
    explicit ChannelPattern(const std::string& regex)
    {
        const std::string anchored = "^" + regex + "$";
        if (regcomp(&re_, anchored.c_str(), REG_EXTENDED | REG_NOSUB) != 0)
            throw BusError("bad channel regex '" + regex + "'");
    }
    ~ChannelPattern() { regfree(&re_); }
    ChannelPattern(const ChannelPattern&) = delete;
    ChannelPattern& operator=(const ChannelPattern&) = delete;
    bool matches(const std::string& channel) const { return regexec(&re_, channel.c_str(), 0, nullptr, 0) == 0; }

private:
    regex_t re_{};
};

class LiveBus final : public Bus
{
public:
    LiveBus(std::string url, const LiveOptions& options)
        : url_(std::move(url)), udpm_(detail::parse_udpm_url(url_))
    {
        limits_.max_message_bytes = options.max_message_bytes;
        lcm_ = lcm_create(url_.c_str());
        if (!lcm_) throw BusError("LCM cannot be created for '" + url_ + "' (bad URL, or no multicast route?)");
    }
    ~LiveBus() override { lcm_destroy(lcm_); }

    bool publish(const std::string& channel, const void* data, std::size_t size) override
    {
        if (size > static_cast<std::size_t>(INT_MAX) || lcm_publish(lcm_, channel.c_str(), data, static_cast<unsigned>(size)) != 0) {
            ++counters_.publish_failures;
            return false;
        }
        return true;
    }

    void subscribe(const std::string& channel_regex, RawHandler handler) override
    {
        if (udpm_) {
            if (udpm_->transmit_only) throw BusError("cannot subscribe on '" + url_ + "': transmit_only=true");
            auto pattern = std::make_unique<ChannelPattern>(channel_regex);
            // The first subscription joins the group: a bus that only publishes receives nothing.
            if (!receiver_) receiver_ = std::make_unique<detail::UdpmReceiver>(*udpm_, limits_);
            subs_.push_back(Sub{this, std::move(handler), std::move(pattern)});
            routes_.clear();
            return;
        }
        subs_.push_back(Sub{this, std::move(handler), nullptr});
        lcm_subscription_t* s = lcm_subscribe(lcm_, channel_regex.c_str(), &LiveBus::on_message, &subs_.back());
        if (!s) throw BusError("cannot subscribe to '" + channel_regex + "' on " + url_);
        // The default queue of 30 drops silently under a burst; a deeper queue costs nothing when idle.
        lcm_subscription_set_queue_capacity(s, 1000);
    }

    HandleResult handle(int timeout_ms) override
    {
        if (!receiver_) {
            if (udpm_) return wait_without_subscriptions(timeout_ms);
            const int rc = lcm_handle_timeout(lcm_, timeout_ms);
            if (rc > 0) return HandleResult::handled;
            if (rc == 0) return HandleResult::timeout;
            return HandleResult::error;
        }
        const int64_t deadline = io::monotonic_us() + int64_t{timeout_ms} * 1000;
        for (;;) {
            // One bounded drain per round: the caller's timers run between rounds.
            const detail::DrainResult r = receiver_->drain(
                [this](std::string_view channel, const uint8_t* data, std::size_t size, int64_t recv_utime) {
                    return dispatch(channel, data, size, recv_utime);
                },
                {}, &wants_);
            const detail::ReassemblyCounters& c = receiver_->reassembly();
            counters_.incomplete_messages = c.incomplete_messages;
            counters_.invalid_datagrams = c.invalid_datagrams;
            counters_.oversized_messages = c.oversized_messages;
            counters_.expired_messages = c.expired_messages;
            counters_.evicted_messages = c.evicted_messages;
            counters_.reassembly_bytes = receiver_->reassembly_bytes_held();
            counters_.receive_budget_stops = receiver_->counters().budget_stops;
            if (r.handed > 0 || r.budget_spent) return HandleResult::handled;
            const int64_t left_us = deadline - io::monotonic_us();
            if (timeout_ms >= 0 && left_us <= 0) return HandleResult::timeout;
            pollfd p{receiver_->fd(), POLLIN, 0};
            const int wait_ms = timeout_ms < 0 ? -1 : static_cast<int>((left_us + 999) / 1000);
            if (::poll(&p, 1, wait_ms) < 0 && errno != EINTR) return HandleResult::error;
        }
    }

    int fd() const override
    {
        if (udpm_) return receiver_ ? receiver_->fd() : -1;
        // liblcm opens its receive socket and joins the group on the first lcm_get_fileno().
        return subs_.empty() ? -1 : lcm_get_fileno(lcm_);
    }
    int64_t now_utime() const override { return io::now_utime(); }
    std::string describe() const override { return url_; }

private:
    struct Sub
    {
        LiveBus* bus;
        RawHandler handler;
        std::unique_ptr<ChannelPattern> pattern;  // udpm only
    };

    // The subscriptions a channel goes to, worked out once per channel name.
    const std::vector<Sub*>& route(std::string_view channel)
    {
        channel_.assign(channel);
        auto it = routes_.find(channel_);
        if (it != routes_.end()) return it->second;
        if (routes_.size() > 4096) routes_.clear();  // random names (a fuzzer, garbage) must not grow it
        std::vector<Sub*> to;
        for (auto& s : subs_)
            if (s.pattern->matches(channel_)) to.push_back(&s);
        return routes_.emplace(channel_, std::move(to)).first->second;
    }

    // Calls the channel's handlers; false when nobody subscribed to it (most datagrams).
    bool dispatch(std::string_view channel, const uint8_t* data, std::size_t size, int64_t recv_utime)
    {
        const std::vector<Sub*>& routed = route(channel);
        if (routed.empty()) return false;
        const std::vector<Sub*> to = routed;  // a copy: a handler may subscribe
        const std::string name = channel_;
        ++counters_.received;
        for (Sub* s : to) detail::call_guarded(s->handler, counters_, name, data, size, recv_utime);
        return true;
    }

    HandleResult wait_without_subscriptions(int timeout_ms)
    {
        if (timeout_ms > 0) ::poll(nullptr, 0, timeout_ms);
        return HandleResult::timeout;
    }

    static void on_message(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
    {
        auto* sub = static_cast<Sub*>(user);
        ++sub->bus->counters_.received;
        detail::call_guarded(sub->handler, sub->bus->counters_, channel, static_cast<const uint8_t*>(rbuf->data),
                             rbuf->data_size, rbuf->recv_utime);
    }

    std::string url_;
    std::optional<detail::UdpmUrl> udpm_;
    lcm_t* lcm_ = nullptr;
    detail::ReassemblyLimits limits_;
    std::unique_ptr<detail::UdpmReceiver> receiver_;
    const detail::LcmReassembler::Wants wants_ = [this](std::string_view channel) { return !route(channel).empty(); };
    std::list<Sub> subs_;  // stable addresses: liblcm and routes_ hold pointers to them
    std::unordered_map<std::string, std::vector<Sub*>> routes_;
    std::string channel_;  // scratch for lookups
};

}  // namespace

std::unique_ptr<Bus> open_live(const std::string& url, const LiveOptions& options)
{
    return std::make_unique<LiveBus>(url, options);
}

}  // namespace ugv::bus
