#include "ugv/io/clock.hpp"

#include <ctime>

namespace ugv::io {

static int64_t read_clock_us(clockid_t id)
{
    timespec ts{};
    clock_gettime(id, &ts);
    return static_cast<int64_t>(ts.tv_sec) * 1'000'000 + ts.tv_nsec / 1000;
}

int64_t now_utime() { return read_clock_us(CLOCK_REALTIME); }
int64_t monotonic_us() { return read_clock_us(CLOCK_MONOTONIC); }

}  // namespace ugv::io
