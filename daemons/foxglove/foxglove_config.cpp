#include "foxglove_config.hpp"

#include <algorithm>
#include <cmath>

#include <asio/ip/address.hpp>

namespace ugv::foxglove_daemon {

namespace {

// An address as typed: echoed in the refusal only when short and printable (one line).
std::string quoted_address(const std::string& a)
{
    constexpr std::size_t kMaxShown = 64;
    const bool printable = std::all_of(a.begin(), a.end(), [](char c) { return c > ' ' && c < 127; });
    if (printable && a.size() <= kMaxShown) return "'" + a + "'";
    return "a value of " + std::to_string(a.size()) + " characters";
}

}  // namespace

FoxgloveConfig read_config(runtime::Config& cfg)
{
    FoxgloveConfig c;
    c.channels = cfg.get_channel_regex("channels", c.channels);
    c.no_raw = cfg.get_string("no_raw", c.no_raw);
    // Empty leaves every raw topic in; otherwise a channel regex with the limits of `channels`.
    if (!c.no_raw.empty())
        if (const std::string why = runtime::Config::channel_regex_problem(c.no_raw); !why.empty()) cfg.fail("no_raw", why);
    c.address = cfg.get_string("address", c.address);
    std::error_code ec;
    (void)asio::ip::make_address(c.address, ec);
    // A NUL would end the text asio parses: "127.0.0.1\0junk" must not pass as 127.0.0.1.
    if (ec || c.address.find('\0') != std::string::npos) cfg.fail("address", quoted_address(c.address) + " is not an IPv4 or IPv6 address");
    c.port = static_cast<int>(cfg.get_int("port", c.port, 1, 65535));
    c.max_clients = static_cast<int>(cfg.get_int("max_clients", c.max_clients, 1, 256));
    c.client_queue_bytes =
        static_cast<std::size_t>(cfg.get_int("client_queue_kb", static_cast<int64_t>(c.client_queue_bytes >> 10), 64,
                                             1 << 20))
        << 10;
    c.status_channel = cfg.get_channel("status_channel", c.status_channel);
    c.health_timeout_us = static_cast<int64_t>(std::llround(cfg.get_double("health_timeout_s", 5.0, 0.1, 600.0) * 1e6));
    return c;
}

}  // namespace ugv::foxglove_daemon
