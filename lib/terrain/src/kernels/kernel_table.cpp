#include "kernel_table.hpp"

#include <atomic>
#include <stdexcept>
#include <string>

#include "float8.hpp"

namespace ugv::terrain::detail {

namespace {

constexpr KernelTable kGeneric{SimdLevel::generic, place_chunk_generic,
                               turn_slots_generic, find_merges_generic, spread_corners_generic,
                               spread_corners_centred_generic};
#if defined(UGV_TERRAIN_HAVE_AVX2)
constexpr KernelTable kAvx2{SimdLevel::avx2, place_chunk_avx2, turn_slots_avx2,
                            find_merges_avx2, spread_corners_avx2, spread_corners_centred_avx2};
#endif

SimdLevel detect()
{
#if defined(UGV_TERRAIN_HAVE_AVX2)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return SimdLevel::avx2;
#endif
    return SimdLevel::generic;
}

std::atomic<const KernelTable*>& chosen()
{
    static std::atomic<const KernelTable*> table{&kernel_table(best_simd_level())};
    return table;
}

}  // namespace

const KernelTable& kernel_table(SimdLevel level)
{
#if defined(UGV_TERRAIN_HAVE_AVX2)
    if (level == SimdLevel::avx2) return kAvx2;
#endif
    (void)level;
    return kGeneric;
}

const KernelTable& kernels() { return *chosen().load(std::memory_order_relaxed); }

}  // namespace ugv::terrain::detail

namespace ugv::terrain {

SimdLevel best_simd_level()
{
    static const SimdLevel best = detail::detect();
    return best;
}

SimdLevel simd_level() { return detail::kernels().level; }

void set_simd_level(SimdLevel level)
{
    if (static_cast<int>(level) > static_cast<int>(best_simd_level()))
        throw std::invalid_argument(std::string("this CPU cannot run the ") + to_string(level) + " code (best: " +
                                    to_string(best_simd_level()) + ")");
    detail::chosen().store(&detail::kernel_table(level), std::memory_order_relaxed);
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
