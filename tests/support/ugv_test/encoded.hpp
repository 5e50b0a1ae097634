// A message's LCM bytes, and one message written as an event of an LCM log: what tests need
// to feed daemons, decoders and log readers without a bus.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace ugv::test {

template <typename T>
std::vector<uint8_t> encoded(const T& msg)
{
    std::vector<uint8_t> buf(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
    return buf;
}

// Appends msg on channel, stamped utime, to an open log.
template <typename T>
void write_event(lcm::LogFile& log, int64_t utime, const std::string& channel, const T& msg)
{
    std::vector<uint8_t> buf = encoded(msg);
    lcm::LogEvent ev{};
    ev.timestamp = utime;
    ev.channel = channel;
    ev.datalen = static_cast<int32_t>(buf.size());
    ev.data = buf.data();
    log.writeEvent(&ev);
}

}  // namespace ugv::test
