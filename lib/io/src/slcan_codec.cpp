#include "ugv/io/slcan_codec.hpp"

#include <cstdio>

namespace ugv::io::slcan {
namespace {

// The longest valid line: "T" + 8 id digits + 1 dlc digit + 16 data digits.
constexpr std::size_t kMaxLine = 1 + 8 + 1 + 16;

int hex_value(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    return -1;
}

bool parse_hex(std::string_view s, uint32_t& out)
{
    out = 0;
    for (const char c : s) {
        const int v = hex_value(c);
        if (v < 0) return false;
        out = (out << 4) | static_cast<uint32_t>(v);
    }
    return true;
}

void append_hex(std::string& out, uint32_t value, int digits)
{
    static const char* kHex = "0123456789ABCDEF";
    for (int k = digits - 1; k >= 0; --k) out += kHex[(value >> (4 * k)) & 0xF];
}

}  // namespace

std::string encode_frame(const CanFrame& f)
{
    std::string s;
    const uint8_t dlc = f.dlc > 8 ? 8 : f.dlc;
    if (f.extended) {
        s += f.rtr ? 'R' : 'T';
        append_hex(s, f.id & 0x1FFFFFFF, 8);
    } else {
        s += f.rtr ? 'r' : 't';
        append_hex(s, f.id & 0x7FF, 3);
    }
    append_hex(s, dlc, 1);
    if (!f.rtr)
        for (uint8_t k = 0; k < dlc; ++k) append_hex(s, f.data[k], 2);
    s += '\r';
    return s;
}

std::optional<std::string> encode_bitrate(int bitrate)
{
    static const int kRates[] = {10000, 20000, 50000, 100000, 125000, 250000, 500000, 800000, 1000000};
    for (int k = 0; k < 9; ++k)
        if (kRates[k] == bitrate) return "S" + std::to_string(k) + "\r";
    return std::nullopt;
}

Event decode_line(std::string_view line)
{
    Event e;
    e.text = std::string(line);
    if (line.empty()) {
        e.kind = Event::Kind::ok;
        return e;
    }
    const char c = line[0];
    if ((c == 'z' || c == 'Z') && line.size() == 1) {
        e.kind = Event::Kind::tx_ack;
        return e;
    }
    const bool ext = (c == 'T' || c == 'R');
    const bool rtr = (c == 'r' || c == 'R');
    if (c != 't' && c != 'T' && c != 'r' && c != 'R') return e;
    const std::size_t id_len = ext ? 8 : 3;
    if (line.size() < 1 + id_len + 1) return e;
    uint32_t id = 0, dlc = 0;
    if (!parse_hex(line.substr(1, id_len), id) || !parse_hex(line.substr(1 + id_len, 1), dlc) || dlc > 8) return e;
    if (id > (ext ? 0x1FFFFFFFu : 0x7FFu)) return e;
    const std::size_t data_len = rtr ? 0 : 2 * dlc;
    // Some adapters append a 4-digit time stamp; accept and ignore it.
    const std::size_t rest = line.size() - (1 + id_len + 1);
    if (rest != data_len && rest != data_len + 4) return e;
    e.frame.id = id;
    e.frame.extended = ext;
    e.frame.rtr = rtr;
    e.frame.dlc = static_cast<uint8_t>(dlc);
    for (std::size_t k = 0; k < data_len / 2; ++k) {
        uint32_t b = 0;
        if (!parse_hex(line.substr(1 + id_len + 1 + 2 * k, 2), b)) return e;
        e.frame.data[k] = static_cast<uint8_t>(b);
    }
    e.kind = Event::Kind::frame;
    return e;
}

std::vector<Event> Decoder::feed(const uint8_t* data, std::size_t n)
{
    std::vector<Event> out;
    for (std::size_t k = 0; k < n; ++k) {
        const char c = static_cast<char>(data[k]);
        if (c == '\a') {
            Event e;
            e.kind = Event::Kind::error;
            out.push_back(e);
            line_.clear();
            continue;
        }
        if (c == '\r' || c == '\n') {
            if (c == '\n' && line_.empty()) continue;  // CR LF: the LF ends nothing
            Event e = decode_line(line_);
            if (e.kind == Event::Kind::malformed) ++malformed_;
            out.push_back(std::move(e));
            line_.clear();
            continue;
        }
        if (line_.size() >= kMaxLine + 4) {
            ++malformed_;  // runaway line: drop it and wait for the next CR
            line_.clear();
            continue;
        }
        line_ += c;
    }
    return out;
}

}  // namespace ugv::io::slcan
