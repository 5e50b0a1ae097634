// The device-clock filter against a simulated device clock with drift and arrival jitter.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "ugv/io/device_clock_filter.hpp"
#include "ugv/microstrain_gx1/tick_unwrapper.hpp"

using ugv::io::DeviceClockFilter;
using ugv::microstrain_gx1::TickUnwrapper;

namespace {

struct Run
{
    double max_error_us = 0;       // after the warm-up
    double max_raw_error_us = 0;   // of the raw arrival stamps, for comparison
    std::size_t samples = 0;
};

// A device whose clock runs `ppm` fast, sending a frame every `ticks_per_frame` ticks of
// 6.5536 ms; the host sees each first byte after a delay of 0..3 ms, and 5 % of frames
// after 10..40 ms more (a loaded machine). The timer is a u16, unwrapped on the host.
Run simulate(double ppm, double duration_s, unsigned seed)
{
    const double tick_s = 6.5536e-3;
    const int ticks_per_frame = 3;
    const int64_t host_start_us = 1'700'000'000'000'000;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter_us(0.0, 3000.0);
    std::uniform_real_distribution<double> late_us(10000.0, 40000.0);
    std::uniform_real_distribution<double> unit(0.0, 1.0);

    DeviceClockFilter filter;
    TickUnwrapper unwrapper;
    Run run;
    const uint32_t first_tick = 60000;  // wraps after 5536 ticks (36 s)
    for (int64_t k = 0;; ++k) {
        const int64_t ticks = first_tick + k * ticks_per_frame;
        const double device_elapsed_s = static_cast<double>(ticks - first_tick) * tick_s;
        // The device clock runs fast: true elapsed time is shorter.
        const double true_elapsed_s = device_elapsed_s / (1.0 + ppm * 1e-6);
        if (true_elapsed_s > duration_s) break;
        const double truth_us = static_cast<double>(host_start_us) + true_elapsed_s * 1e6;
        double delay_us = jitter_us(rng);
        if (unit(rng) < 0.05) delay_us += late_us(rng);
        const auto arrival = static_cast<int64_t>(std::llround(truth_us + delay_us));
        const int64_t unwrapped = unwrapper.unwrap(static_cast<uint16_t>(ticks & 0xFFFF));
        const int64_t stamp = filter.update(static_cast<double>(unwrapped) * tick_s, arrival);
        if (true_elapsed_s >= 2.0) {
            run.max_error_us = std::max(run.max_error_us, std::abs(static_cast<double>(stamp) - truth_us));
            run.max_raw_error_us = std::max(run.max_raw_error_us, delay_us);
        }
        ++run.samples;
    }
    return run;
}

}  // namespace

TEST_CASE("a 100 ppm device clock with arrival jitter stays within 1 ms over ten minutes", "[gx1][clock]")
{
    for (double ppm : {100.0, -100.0}) {
        const Run run = simulate(ppm, 600.0, 42);
        INFO("ppm " << ppm << " max error " << run.max_error_us << " us, raw " << run.max_raw_error_us << " us");
        CHECK(run.samples > 30000);  // 600 s at 3 ticks of 6.5536 ms
        CHECK(run.max_raw_error_us > 30000.0);  // the raw stamps really are bad
        CHECK(run.max_error_us < 1000.0);
    }
}

TEST_CASE("the drift estimate converges to the simulated clock error", "[gx1][clock]")
{
    DeviceClockFilter filter;
    // No jitter: a device 100 ppm fast means host seconds per device second = 1/(1+1e-4).
    for (int k = 0; k < 100 * 120; ++k) {
        const double device_s = k * 0.01;
        const auto arrival = static_cast<int64_t>(std::llround(device_s / (1.0 + 1e-4) * 1e6));
        filter.update(device_s, 1'000'000'000 + arrival);
    }
    CHECK(filter.drift() == Approx(1.0 / (1.0 + 1e-4) - 1.0).margin(2e-6));
}

TEST_CASE("a device timer that restarts restarts the model", "[gx1][clock]")
{
    DeviceClockFilter filter;
    int64_t stamp = 0;
    for (int k = 0; k < 500; ++k) stamp = filter.update(100.0 + k * 0.01, 5'000'000 + k * 10'000);
    CHECK(stamp == 5'000'000 + 499 * 10'000);
    // The device was power-cycled: its time jumps back to 0; host time goes on.
    stamp = filter.update(0.0, 10'000'000);
    CHECK(filter.restarts() == 1);
    CHECK(stamp == 10'000'000);
    stamp = filter.update(0.01, 10'010'000);
    CHECK(stamp == 10'010'000);
}
