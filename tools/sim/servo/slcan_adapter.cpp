#include "slcan_adapter.hpp"

#include <cstdio>
#include <utility>

#include "ugv/io/slcan_codec.hpp"

namespace ugv::sim::servo {

void SlcanAdapter::bell()
{
    output_ += '\a';
    ++errors_;
}

std::string SlcanAdapter::stamp(int64_t now_us) const
{
    if (!timestamps_) return "";
    char buf[8];
    std::snprintf(buf, sizeof buf, "%04X", static_cast<unsigned>((now_us / 1000) % 60000));  // ms, wraps at 60000
    return buf;
}

std::vector<io::CanFrame> SlcanAdapter::feed(const uint8_t* data, std::size_t n, int64_t now_us)
{
    std::vector<io::CanFrame> frames;
    for (std::size_t i = 0; i < n; ++i) {
        const char c = static_cast<char>(data[i]);
        if (c == '\r') {
            command(line_, now_us, frames);
            line_.clear();
        } else if (c != '\n') {
            if (line_.size() < 64) line_ += c;  // a runaway line ends in BEL at its CR
            else line_ = "!";
        }
    }
    return frames;
}

void SlcanAdapter::command(const std::string& line, int64_t now_us, std::vector<io::CanFrame>& frames)
{
    (void)now_us;
    if (line.empty()) {
        output_ += '\r';  // an empty command is a no-op that answers OK
        return;
    }
    switch (line[0]) {
    case 'S':
        if (open_ || line.size() != 2 || line[1] < '0' || line[1] > '8') return bell();
        bitrate_code_ = line[1] - '0';
        output_ += '\r';
        return;
    case 'O':
    case 'L':
        if (open_ || bitrate_code_ < 0) return bell();
        open_ = true;
        listen_only_ = line[0] == 'L';
        output_ += '\r';
        return;
    case 'C':
        if (!open_) return bell();
        open_ = false;
        bus_off_ = false;  // closing resets the controller
        output_ += '\r';
        return;
    case 'F': output_ += "F00\r"; return;
    case 'V': output_ += "V1013\r"; return;
    case 'N': output_ += "NSIM1\r"; return;
    case 'Z':
        if (line.size() != 2 || (line[1] != '0' && line[1] != '1')) return bell();
        timestamps_ = line[1] == '1';
        output_ += '\r';
        return;
    case 't':
    case 'T':
    case 'r':
    case 'R': {
        const auto e = io::slcan::decode_line(line);
        if (!open_ || listen_only_ || bus_off_ || e.kind != io::slcan::Event::Kind::frame) return bell();
        if (refuse_tx_every_ > 0 && ++transmits_ % refuse_tx_every_ == 0) {
            ++tx_refused_;
            return bell();
        }
        if (bitrate_matches()) frames.push_back(e.frame);
        output_ += (line[0] == 't' || line[0] == 'r') ? "z\r" : "Z\r";
        return;
    }
    default: return bell();
    }
}

void SlcanAdapter::bus_off()
{
    if (!open_ || bus_off_) return;
    bus_off_ = true;
    bell();
}

void SlcanAdapter::on_bus_frame(const io::CanFrame& frame, int64_t now_us)
{
    if (!open_ || bus_off_ || !bitrate_matches()) return;
    std::string s = io::slcan::encode_frame(frame);
    if (timestamps_ && !s.empty() && s.back() == '\r') s.insert(s.size() - 1, stamp(now_us));
    output_ += s;
}

}  // namespace ugv::sim::servo
