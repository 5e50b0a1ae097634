// LCM behind a small interface, with three implementations:
//   live   - any LCM URL (udpm multicast, memq for in-process tests); udpm is received on
//            the caller's thread, without liblcm's receive thread (live_bus.cpp);
//   replay - reads an LCM log in order and dispatches each event, as fast as the CPU allows,
//            deterministically (the processing daemons' --replay);
//   writer - publishing appends events to an LCM log (the processing daemons' --out).
// Handlers receive raw bytes; ugv/bus/typed.hpp decodes them into ugv types. Nothing throws
// through LCM's C callbacks: a handler's exception is caught, counted and logged.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

namespace ugv::bus {

class BusError : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

// channel, bytes, and the time the bus received them (us since the epoch; for replay, the
// time stamp in the log).
using RawHandler = std::function<void(const std::string& channel, const uint8_t* data, std::size_t size,
                                      int64_t recv_utime)>;

enum class HandleResult { handled, timeout, end, error };

struct BusCounters
{
    uint64_t received = 0;         // messages dispatched to at least one handler
    uint64_t decode_failures = 0;  // messages a typed handler could not decode (dropped)
    uint64_t handler_errors = 0;   // exceptions caught from handlers
    uint64_t publish_failures = 0;
    // Live udpm only (the receiver and its reassembly, docs/runtime.md "LCM input"):
    uint64_t incomplete_messages = 0;  // fragmented messages that lost a fragment
    uint64_t invalid_datagrams = 0;    // datagrams on the port that are not LCM's
    uint64_t oversized_messages = 0;   // fragmented messages over max_message_bytes, refused
    uint64_t expired_messages = 0;     // unfinished fragmented messages dropped for their age
    uint64_t evicted_messages = 0;     // unfinished ones dropped to stay within the memory bound
    uint64_t reassembly_bytes = 0;     // held now for unfinished messages (a level, not a count)
    uint64_t receive_budget_stops = 0; // reads that stopped at their budget: a flood, or a burst

    template <class F>
    void visit(F&& f) const
    {
        f("received", received);
        f("decode_failures", decode_failures);
        f("handler_errors", handler_errors);
        f("publish_failures", publish_failures);
        f("incomplete_messages", incomplete_messages);
        f("invalid_datagrams", invalid_datagrams);
        f("oversized_messages", oversized_messages);
        f("expired_messages", expired_messages);
        f("evicted_messages", evicted_messages);
        f("reassembly_bytes", reassembly_bytes);
        f("receive_budget_stops", receive_budget_stops);
    }
};

class Bus
{
public:
    virtual ~Bus() = default;
    virtual bool publish(const std::string& channel, const void* data, std::size_t size) = 0;
    // channel_regex is matched against the whole channel name, as LCM does.
    virtual void subscribe(const std::string& channel_regex, RawHandler handler) = 0;
    // Dispatches what is waiting (live: waits up to timeout_ms; replay: the next event).
    // Live udpm reads a bounded number of datagrams per call and returns handled when it
    // dispatched something or stopped at that bound (more may be waiting).
    virtual HandleResult handle(int timeout_ms) = 0;
    // For poll(): readable when handle() has something to do. -1 when not pollable (replay)
    // or when a live bus has no subscription (then it does not receive at all).
    virtual int fd() const { return -1; }
    // The time of the event being dispatched (replay) or now (live), us since the epoch.
    virtual int64_t now_utime() const = 0;
    virtual std::string describe() const = 0;

    BusCounters& counters() { return counters_; }
    const BusCounters& counters() const { return counters_; }

protected:
    BusCounters counters_;
};

// The largest fragmented message a live udpm bus accepts by default: ugv-terrain's map
// (150 x 150 cells, 444 KiB) with room to spare.
constexpr std::size_t kDefaultMaxMessageBytes = 1u << 20;

struct LiveOptions
{
    // udpm: a fragmented message that claims more is refused and counted; unfinished ones
    // hold at most 4 x this together (docs/runtime.md "LCM input").
    std::size_t max_message_bytes = kDefaultMaxMessageBytes;
};

// LCM_DEFAULT_URL if set, else "udpm://239.255.76.67:7667?ttl=0".
std::string default_url();
// Throws BusError when LCM cannot be created for url (one line naming the URL).
std::unique_ptr<Bus> open_live(const std::string& url, const LiveOptions& options = {});
// Throws BusError when path cannot be opened as an LCM log.
std::unique_ptr<Bus> open_log_replay(const std::string& path);
// Publishing appends events to a new log at path, each stamped with clock() (the replay
// bus's event time, so output logs are bit-identical run to run). Throws BusError.
std::unique_ptr<Bus> open_log_writer(const std::string& path, std::function<int64_t()> clock);

}  // namespace ugv::bus
