// Typed publish and subscribe for lcm-gen message classes on a ugv::bus::Bus.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "ugv/bus/bus.hpp"
#include "ugv/reflect.hpp"

namespace ugv::bus {

template <typename T>
bool publish(Bus& bus, const std::string& channel, const T& msg)
{
    const int size = msg.getEncodedSize();
    std::vector<uint8_t> buf(static_cast<std::size_t>(size));
    if (msg.encode(buf.data(), 0, size) != size) {
        ++bus.counters().publish_failures;
        return false;
    }
    return bus.publish(channel, buf.data(), buf.size());
}

// Decodes bytes as T, the checked way: false for anything that is not exactly one T (wrong
// type, truncated, random bytes, lengths that lie). The bytes are checked against the type's
// schema first (reflect::well_formed), because lcm-gen's decode() throws or over-allocates
// on some malformed input. For tools that read logs as well as for subscribe().
template <typename T>
bool decode_checked(const void* data, std::size_t size, T& msg)
{
    return size <= static_cast<std::size_t>(std::numeric_limits<int>::max()) &&
           reflect::well_formed(data, size) &&
           msg.decode(data, 0, static_cast<int>(size)) == static_cast<int>(size);
}

// handler(channel, message, recv_utime). A message that does not decode as T (wrong type,
// truncated, random bytes, lengths that lie) is counted in bus.counters().decode_failures and
// dropped (decode_checked).
template <typename T>
void subscribe(Bus& bus, const std::string& channel_regex,
               std::function<void(const std::string&, const T&, int64_t)> handler)
{
    Bus* b = &bus;
    bus.subscribe(channel_regex, [b, handler = std::move(handler)](const std::string& channel, const uint8_t* data,
                                                                   std::size_t size, int64_t recv_utime) {
        T msg;
        if (!decode_checked(data, size, msg)) {
            ++b->counters().decode_failures;
            return;
        }
        handler(channel, msg, recv_utime);
    });
}

}  // namespace ugv::bus
