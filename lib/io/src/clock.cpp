#include "ugv/io/clock.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>

namespace ugv::io {

static int64_t read_clock_us(clockid_t id)
{
    timespec ts{};
    clock_gettime(id, &ts);
    return static_cast<int64_t>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

std::optional<int64_t> parse_clock_offset(const char* text, std::string& why)
{
    if (text == nullptr || *text == '\0') return 0;
    errno = 0;
    char* end = nullptr;
    const double s = std::strtod(text, &end);
    if (end == text || *end != '\0' || errno != 0 || !std::isfinite(s)) {
        why = "not a number of seconds";
        return std::nullopt;
    }
    if (std::fabs(s) > 86400.0) {
        why = "must be within -86400..86400 s";
        return std::nullopt;
    }
    return static_cast<int64_t>(std::llround(s * 1e6));
}

int64_t clock_test_offset_us()
{
    // Read once: every stamp of the process is shifted by the same amount.
    static const int64_t offset = [] {
        const char* text = std::getenv(kClockOffsetEnv);
        std::string why;
        const auto v = parse_clock_offset(text, why);
        if (!v) {
            std::fprintf(stderr, "%s=%s: %s\n", kClockOffsetEnv, text, why.c_str());
            std::fflush(stderr);
            std::_Exit(2);
        }
        return *v;
    }();
    return offset;
}

int64_t now_utime() { return read_clock_us(CLOCK_REALTIME) + clock_test_offset_us(); }
int64_t monotonic_us() { return read_clock_us(CLOCK_MONOTONIC); }

}  // namespace ugv::io
