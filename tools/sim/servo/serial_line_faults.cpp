#include "serial_line_faults.hpp"

#include "ugv/sim/line_faults.hpp"

namespace ugv::sim::servo {

SerialLineFaults::SerialLineFaults(const SerialLineFaultConfig& config)
    : config_(config), rng_(config.seed), bit_error_rng_(config.seed + 1)
{
}

void SerialLineFaults::append_line(std::string& out, const std::string& line)
{
    // line ends in its terminator (CR, or BEL alone).
    const bool frame_line = line.size() > 2 && (line[0] == 't' || line[0] == 'T') && line.back() == '\r';
    if (frame_line && config_.truncate_every > 0 && ++frame_lines_ % config_.truncate_every == 0) {
        const std::size_t body = line.size() - 1;
        const std::size_t keep = std::uniform_int_distribution<std::size_t>(1, body - 1)(rng_);
        out.append(line, 0, keep);
        out += '\r';
        ++lines_truncated_;
        return;
    }
    out += line;
}

std::string SerialLineFaults::apply(const std::string& output, bool garbage_now)
{
    std::string out;
    if (garbage_now) {
        std::uniform_int_distribution<int> byte(0, 255);
        for (std::size_t i = 0; i < config_.garbage_bytes; ++i) {
            int b = byte(rng_);
            if (b == '\a') b = 0;  // a BEL is the adapter saying "error": not line noise
            out += static_cast<char>(b);
        }
        garbage_sent_ += config_.garbage_bytes;
    }
    std::string line;
    for (const char c : output) {
        line += c;
        if (c == '\r' || c == '\a') {
            append_line(out, line);
            line.clear();
        }
    }
    out += line;  // an unterminated tail (the adapter never leaves one)
    bytes_damaged_ += flip_bits(out.begin(), out.end(), config_.bit_error_rate, bit_error_rng_);
    return out;
}

}  // namespace ugv::sim::servo
