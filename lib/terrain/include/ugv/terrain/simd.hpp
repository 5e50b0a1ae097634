// Which vector code the terrain library's hot loops run. The library is built for the
// architecture's baseline (x86-64: SSE2), so that one package runs on any vehicle computer;
// where the CPU has AVX2 and FMA (x86-64 since 2013-2015) the placement of points in the
// fusion loop and the rotation of the egocentric map run 8-wide code compiled for them.
// Each level is one table of the kernels (src/kernels/kernel_table.hpp), chosen once at
// start-up; the map calls the kernels only through the table in use.
#pragma once

namespace ugv::terrain {

enum class SimdLevel : int {
    generic = 0,  // 4-float vectors: SSE2 on x86-64, NEON on ARM, scalar code elsewhere
    avx2 = 1,     // 8-float vectors with FMA (x86-64 only)
};

// The level in use: the best the CPU has, unless set_simd_level chose a lower one.
SimdLevel simd_level();
// The best level this CPU runs.
SimdLevel best_simd_level();
// Tests and benchmarks run the generic code on an AVX2 CPU with this. Throws
// std::invalid_argument for a level the CPU cannot run.
void set_simd_level(SimdLevel level);
const char* to_string(SimdLevel level);

// set_simd_level for a scope: the level before comes back when it ends, whatever the way
// out (a failed test assertion included).
class ScopedSimdLevel
{
public:
    explicit ScopedSimdLevel(SimdLevel level) : previous_(simd_level()) { set_simd_level(level); }
    ~ScopedSimdLevel() { set_simd_level(previous_); }
    ScopedSimdLevel(const ScopedSimdLevel&) = delete;
    ScopedSimdLevel& operator=(const ScopedSimdLevel&) = delete;

private:
    SimdLevel previous_;
};

}  // namespace ugv::terrain
