// The live bus: LCM's C API (lcm_t) for any URL. The C API takes a plain callback with a
// user pointer, so handlers can be any std::function without LCM 1.4's lambda support.
#include <lcm/lcm.h>
#include <poll.h>

#include <list>

#include "handler_guard.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/bus/bus.hpp"

namespace ugv::bus {
namespace {

class LiveBus final : public Bus
{
public:
    explicit LiveBus(std::string url) : url_(std::move(url))
    {
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
        subs_.push_back(Sub{this, std::move(handler)});
        lcm_subscription_t* s = lcm_subscribe(lcm_, channel_regex.c_str(), &LiveBus::on_message, &subs_.back());
        if (!s) throw BusError("cannot subscribe to '" + channel_regex + "' on " + url_);
        // The default queue of 30 drops silently under a burst (a map is 225 kB in many
        // fragments); a deeper queue costs nothing when idle.
        lcm_subscription_set_queue_capacity(s, 1000);
    }

    HandleResult handle(int timeout_ms) override
    {
        const int rc = lcm_handle_timeout(lcm_, timeout_ms);
        if (rc > 0) return HandleResult::handled;
        if (rc == 0) return HandleResult::timeout;
        return HandleResult::error;
    }

    // LCM 1.3.1 opens its receive socket and joins the multicast group on the first call of
    // lcm_get_fileno(); from then on every datagram of every channel on the group reaches this
    // process (a map alone is ~190 fragments per publication). A bus that subscribes to
    // nothing -- the device daemons only publish -- never asks, and so receives nothing.
    int fd() const override { return subs_.empty() ? -1 : lcm_get_fileno(lcm_); }
    int64_t now_utime() const override { return io::now_utime(); }
    std::string describe() const override { return url_; }

private:
    struct Sub
    {
        LiveBus* bus;
        RawHandler handler;
    };

    static void on_message(const lcm_recv_buf_t* rbuf, const char* channel, void* user)
    {
        auto* sub = static_cast<Sub*>(user);
        ++sub->bus->counters_.received;
        detail::call_guarded(sub->handler, sub->bus->counters_, channel, static_cast<const uint8_t*>(rbuf->data),
                             rbuf->data_size, rbuf->recv_utime);
    }

    std::string url_;
    lcm_t* lcm_ = nullptr;
    std::list<Sub> subs_;  // stable addresses: LCM holds pointers to them
};

}  // namespace

std::unique_ptr<Bus> open_live(const std::string& url) { return std::make_unique<LiveBus>(url); }

}  // namespace ugv::bus
