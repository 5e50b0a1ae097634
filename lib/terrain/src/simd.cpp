#include "ugv/terrain/simd.hpp"

#include <atomic>
#include <stdexcept>
#include <string>

namespace ugv::terrain {

namespace {

SimdLevel detect()
{
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return SimdLevel::avx2;
#endif
    return SimdLevel::generic;
}

std::atomic<SimdLevel>& chosen()
{
    static std::atomic<SimdLevel> level{best_simd_level()};
    return level;
}

}  // namespace

SimdLevel best_simd_level()
{
    static const SimdLevel best = detect();
    return best;
}

SimdLevel simd_level() { return chosen().load(std::memory_order_relaxed); }

void set_simd_level(SimdLevel level)
{
    if (static_cast<int>(level) > static_cast<int>(best_simd_level()))
        throw std::invalid_argument(std::string("this CPU cannot run the ") + to_string(level) + " code (best: " +
                                    to_string(best_simd_level()) + ")");
    chosen().store(level, std::memory_order_relaxed);
}

const char* to_string(SimdLevel level)
{
    switch (level) {
    case SimdLevel::generic: return "generic";
    case SimdLevel::avx2: return "avx2";
    }
    return "unknown";
}

}  // namespace ugv::terrain
