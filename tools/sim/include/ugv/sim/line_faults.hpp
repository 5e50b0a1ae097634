// Line faults shared by the serial-device emulators (ugv-sim lms, gps, imu): what a noisy
// or interrupted serial line does to the bytes a device sends. Pure functions of a seeded
// generator, so a fault plan with a given seed damages the same bytes every run.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <random>

namespace ugv::sim {

// Flips one random bit in each byte of [first, last) with probability rate (a bit error rate
// per byte, as a UART sees a corrupted character). Returns the number of bytes damaged.
// Draws nothing from rng when rate is 0, so adding the fault off leaves other faults' draws
// (and their outcomes) as they were.
template <typename It>
std::size_t flip_bits(It first, It last, double rate, std::mt19937& rng)
{
    if (rate <= 0.0) return 0;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::uniform_int_distribution<int> bit(0, 7);
    std::size_t damaged = 0;
    for (It it = first; it != last; ++it) {
        if (u(rng) >= rate) continue;
        *it = static_cast<typename std::iterator_traits<It>::value_type>(static_cast<uint8_t>(*it) ^ (1u << bit(rng)));
        ++damaged;
    }
    return damaged;
}

// The length a frame of `size` (>= 2) bytes is cut to: its first k bytes, k uniform in
// [1, size - 1] (the rest never leaves the device).
inline std::size_t cut_length(std::size_t size, std::mt19937& rng)
{
    return std::uniform_int_distribution<std::size_t>(1, size - 1)(rng);
}

// With probability p, cut_length(size); otherwise size.
inline std::size_t truncated_length(std::size_t size, double p, std::mt19937& rng)
{
    if (p <= 0.0 || size < 2) return size;
    std::uniform_real_distribution<double> u(0.0, 1.0);
    if (u(rng) >= p) return size;
    return cut_length(size, rng);
}

}  // namespace ugv::sim
