// The parts of an LCM udpm URL ("udpm://239.255.76.67:7667?ttl=0&recv_buf_size=2097152")
// that the receiving side needs. Pure parsing.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace ugv::bus::detail {

struct UdpmUrl
{
    std::string group = "239.255.76.67";  // liblcm's defaults when the URL leaves them out
    uint16_t port = 7667;
    int ttl = 0;
    int recv_buf_size = 0;  // bytes asked of SO_RCVBUF; 0: the system default
    bool transmit_only = false;
};

// nullopt for another provider (memq://, file://); throws BusError, naming the URL and the
// part that is wrong, for a udpm URL that is malformed (the address is checked by the caller).
std::optional<UdpmUrl> parse_udpm_url(const std::string& url);

}  // namespace ugv::bus::detail
