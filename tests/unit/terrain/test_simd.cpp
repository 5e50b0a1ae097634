#include <catch2/catch.hpp>

#include <fstream>
#include <stdexcept>
#include <string>

#include "ugv/terrain/simd.hpp"

using namespace ugv::terrain;

TEST_CASE("the SIMD level can be lowered for tests, never raised above the CPU's")
{
    CHECK(simd_level() == best_simd_level());
    set_simd_level(SimdLevel::generic);
    CHECK(simd_level() == SimdLevel::generic);
    if (best_simd_level() == SimdLevel::generic)
        CHECK_THROWS_AS(set_simd_level(SimdLevel::avx2), std::invalid_argument);
    set_simd_level(best_simd_level());
    CHECK(std::string(to_string(SimdLevel::avx2)) == "avx2");
}

TEST_CASE("the best SIMD level is the one the CPU's flags in /proc/cpuinfo allow")
{
#if defined(__x86_64__)
    std::ifstream cpuinfo("/proc/cpuinfo");
    std::string line;
    bool avx2 = false, fma = false;
    while (std::getline(cpuinfo, line)) {
        if (line.rfind("flags", 0) != 0) continue;
        avx2 = line.find(" avx2") != std::string::npos;
        fma = line.find(" fma") != std::string::npos;
        break;
    }
    CHECK((best_simd_level() == SimdLevel::avx2) == (avx2 && fma));
#else
    CHECK(best_simd_level() == SimdLevel::generic);
#endif
}

TEST_CASE("ScopedSimdLevel gives the level before back at the end of its scope")
{
    {
        const ScopedSimdLevel use(SimdLevel::generic);
        CHECK(simd_level() == SimdLevel::generic);
    }
    CHECK(simd_level() == best_simd_level());
}
