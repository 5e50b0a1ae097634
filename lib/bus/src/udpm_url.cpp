#include "ugv/bus/udpm_url.hpp"

#include <charconv>

#include "ugv/bus/bus.hpp"

namespace ugv::bus::detail {
namespace {

bool to_int(const std::string& text, long long lo, long long hi, long long& value)
{
    const char* end = text.data() + text.size();
    const auto r = std::from_chars(text.data(), end, value);
    return r.ec == std::errc{} && r.ptr == end && value >= lo && value <= hi;
}

}  // namespace

std::optional<UdpmUrl> parse_udpm_url(const std::string& url)
{
    const std::string scheme = "udpm://";
    if (url.compare(0, scheme.size(), scheme) != 0) return std::nullopt;
    const auto fail = [&](const std::string& why) { return BusError("LCM URL '" + url + "': " + why); };
    UdpmUrl u;
    std::string rest = url.substr(scheme.size());
    std::string query;
    if (const auto q = rest.find('?'); q != std::string::npos) {
        query = rest.substr(q + 1);
        rest.resize(q);
    }
    if (!rest.empty()) {
        const auto colon = rest.rfind(':');
        u.group = rest.substr(0, colon);
        if (colon != std::string::npos) {
            long long port = 0;
            if (!to_int(rest.substr(colon + 1), 1, 65535, port)) throw fail("port must be 1..65535");
            u.port = static_cast<uint16_t>(port);
        }
        if (u.group.empty()) throw fail("no multicast address before the port");
    }
    std::size_t start = 0;
    while (start < query.size()) {
        std::size_t amp = query.find('&', start);
        if (amp == std::string::npos) amp = query.size();
        const std::string option = query.substr(start, amp - start);
        start = amp + 1;
        if (option.empty()) continue;
        const auto eq = option.find('=');
        if (eq == std::string::npos) throw fail("option '" + option + "' has no value");
        const std::string key = option.substr(0, eq), value = option.substr(eq + 1);
        long long n = 0;
        if (key == "ttl") {
            if (!to_int(value, 0, 255, n)) throw fail("ttl must be 0..255");
            u.ttl = static_cast<int>(n);
        } else if (key == "recv_buf_size") {
            if (!to_int(value, 0, 1LL << 30, n)) throw fail("recv_buf_size must be 0..1073741824 bytes");
            u.recv_buf_size = static_cast<int>(n);
        } else if (key == "transmit_only") {
            if (value != "true" && value != "false") throw fail("transmit_only must be true or false");
            u.transmit_only = value == "true";
        } else {
            throw fail("unknown option '" + key + "' (known: ttl, recv_buf_size, transmit_only)");
        }
    }
    return u;
}

}  // namespace ugv::bus::detail
