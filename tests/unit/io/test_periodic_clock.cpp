// The periodic-message clock against a simulated LMS mirror (a scan every 26.67 ms): arrival
// delays from scheduling and stalls, telegrams lost to CRC errors, a mirror off its 75 Hz.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include "ugv/io/periodic_clock.hpp"

using ugv::io::PeriodicClock;

namespace {

constexpr int64_t kHostStartUs = 1'700'000'000'000'000;
constexpr double kScanPeriodS = 2.0 / 75.0;  // 0.5 deg: two sweeps of the 75 Hz mirror

struct Run
{
    std::vector<double> errors_us;  // |stamp - truth| after the first 2 s
    double max_raw_error_us = 0;    // of the unfiltered arrivals, for comparison
    bool ever_later_than_arrival = false;
    uint64_t restarts = 0;
    double percentile(double p) const
    {
        std::vector<double> e = errors_us;
        std::sort(e.begin(), e.end());
        return e[static_cast<std::size_t>(p * static_cast<double>(e.size() - 1))];
    }
};

// Scans end every period * (1 + mirror_error); the host reads each 0..1 ms later. With
// probability stall_p per scan the host process stalls for 30..80 ms and then reads every
// telegram that arrived meanwhile at once (one chunk time, the worst case). With probability
// lost_p a telegram is lost to a CRC error, which the decoder reports.
Run simulate(double mirror_error, double stall_p, double lost_p, double duration_s, unsigned seed)
{
    const double nominal_s = kScanPeriodS;
    const double period_s = nominal_s * (1.0 + mirror_error);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter_us(0.0, 1000.0), stall_us(30'000.0, 80'000.0), unit(0.0, 1.0);
    PeriodicClock clock(nominal_s);
    Run run;
    double stalled_until_us = 0;
    int lost = 0;
    for (int64_t k = 0;; ++k) {
        const double t_s = static_cast<double>(k) * period_s;
        if (t_s > duration_s) break;
        const double truth_us = static_cast<double>(kHostStartUs) + t_s * 1e6;
        if (truth_us >= stalled_until_us && unit(rng) < stall_p) stalled_until_us = truth_us + stall_us(rng);
        if (unit(rng) < lost_p) {
            ++lost;
            continue;
        }
        const double arrival_us = std::max(truth_us, stalled_until_us) + jitter_us(rng);
        const auto arrival = static_cast<int64_t>(std::llround(arrival_us));
        const int64_t stamp = clock.update(arrival, std::exchange(lost, 0));
        run.ever_later_than_arrival |= stamp > arrival;
        if (t_s >= 2.0) {
            run.errors_us.push_back(std::abs(static_cast<double>(stamp) - truth_us));
            run.max_raw_error_us = std::max(run.max_raw_error_us, arrival_us - truth_us);
        }
    }
    run.restarts = clock.restarts();
    return run;
}

}  // namespace

TEST_CASE("Scan stamps follow the mirror through scheduling jitter, stalls and lost telegrams")
{
    const Run r = simulate(0.003, 0.02, 0.01, 300.0, 7);
    INFO("p50 " << r.percentile(0.5) << " us, p99 " << r.percentile(0.99) << " us, p99.9 " << r.percentile(0.999)
                << " us, max " << r.percentile(1.0) << " us; raw max " << r.max_raw_error_us << " us; restarts "
                << r.restarts);
    CHECK(r.max_raw_error_us > 60'000);
    CHECK_FALSE(r.ever_later_than_arrival);
    CHECK(r.percentile(0.5) < 200);
    CHECK(r.percentile(0.99) < 1'000);
    CHECK(r.percentile(1.0) < 5'000);
}

TEST_CASE("Without delays the stamps are the arrivals")
{
    PeriodicClock clock(kScanPeriodS);
    for (int k = 0; k < 200; ++k) {
        const int64_t arrival = kHostStartUs + std::llround(k * 26'666.667);
        CHECK(std::llabs(clock.update(arrival) - arrival) <= 1);
    }
    CHECK(clock.restarts() == 0);
}

TEST_CASE("A telegram the decoder rejected advances the count by two periods")
{
    PeriodicClock clock(kScanPeriodS);
    const double p_us = 26'666.667;
    for (int k = 0; k < 100; ++k) clock.update(kHostStartUs + std::llround(k * p_us));
    // Scan 100 lost to a CRC error; 101 arrives 5 ms late, 102 on time: both on the grid.
    CHECK(std::llabs(clock.update(kHostStartUs + std::llround(101 * p_us) + 5'000, 1) -
                     (kHostStartUs + std::llround(101 * p_us))) <= 2);
    CHECK(std::llabs(clock.update(kHostStartUs + std::llround(102 * p_us)) - (kHostStartUs + std::llround(102 * p_us))) <=
          2);
    CHECK(clock.restarts() == 0);
}

TEST_CASE("A telegram that vanished unnoticed is found out and the clock starts again")
{
    PeriodicClock clock(kScanPeriodS);
    const double p_us = 26'666.667;
    auto at = [&](int k) { return kHostStartUs + std::llround(k * p_us); };
    for (int k = 0; k < 100; ++k) clock.update(at(k));
    // 100 never arrives and the decoder saw nothing: from 101 on the count is one short.
    int64_t last_error = 0;
    int k = 101;
    for (; k < 102 + PeriodicClock::kLateBeforeRestart + 1; ++k) last_error = clock.update(at(k)) - at(k);
    CHECK(clock.restarts() == 1);
    CHECK(std::llabs(last_error) <= 2);
    for (; k < 200; ++k) CHECK(std::llabs(clock.update(at(k)) - at(k)) <= 2);
}

TEST_CASE("A line too slow for every scan: every n-th scan, on the grid")
{
    // 361 values at 38400 baud take 191 ms on the line: every 8th scan of 26.7 ms is sent.
    const double p_us = 26'666.667;
    PeriodicClock clock(kScanPeriodS, 8);
    for (int k = 0; k < 100; ++k) {
        const int64_t truth = kHostStartUs + std::llround(8 * k * p_us);
        const int64_t arrival = truth + (k % 3 == 0 ? 0 : 9'000);
        CHECK(clock.update(arrival) - truth <= (k < 3 ? 9'000 : 2));
    }
    CHECK(clock.restarts() == 0);
}

namespace {

// A drive's 100 Hz event-timer TPDOs, 20 ppm off the host's clock, read the way ugv-servo
// reads an slcan adapter once the drive is running: on its own 10 ms control tick (so a
// frame waits in the port's buffer for a fixed phase of that tick), except during a 50 ms
// window every 500 ms in which it wakes for each frame (0.1..0.6 ms after it arrived).
struct LateReads
{
    std::vector<double> errors_us;  // stamp - truth, after the first 2 s
    uint64_t restarts = 0;
};

LateReads read_on_tick(double tick_phase_ms, bool late_reads_fitted, int vanish_at = -1)
{
    constexpr double kTpdoPeriodS = 0.010;
    const double period_us = kTpdoPeriodS * 1e6 * (1.0 + 2e-5);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> prompt_us(100.0, 600.0);
    PeriodicClock clock(kTpdoPeriodS);
    LateReads r;
    for (int k = 0; k < 6000; ++k) {
        if (k == vanish_at) continue;  // lost without the decoder seeing anything
        const double truth_us = static_cast<double>(kHostStartUs) + k * period_us;
        const double host_ms = (truth_us - static_cast<double>(kHostStartUs)) * 1e-3;
        const bool in_window = std::fmod(host_ms, 500.0) < 50.0;
        int64_t stamp = 0;
        if (in_window || k < 10) {
            stamp = clock.update(std::llround(truth_us + prompt_us(rng)));
        } else {
            // The next control tick: ticks at tick_phase_ms + 10 ms * n of the host clock.
            const double wait_ms = std::fmod(tick_phase_ms - std::fmod(host_ms, 10.0) + 10.0, 10.0);
            const auto read = std::llround(truth_us + wait_ms * 1e3);
            stamp = late_reads_fitted ? clock.update(read) : clock.update_read_late(read);
            CHECK(stamp <= read);
        }
        if (k >= 200) r.errors_us.push_back(static_cast<double>(stamp) - truth_us);
    }
    r.restarts = clock.restarts();
    return r;
}

double max_abs(const std::vector<double>& v)
{
    double m = 0;
    for (double e : v) m = std::max(m, std::abs(e));
    return m;
}

}  // namespace

TEST_CASE("Frames read late on a timer are stamped on the line the promptly read ones fit")
{
    for (double phase_ms : {0.5, 3.0, 7.0, 9.5}) {
        const LateReads good = read_on_tick(phase_ms, false);
        INFO("tick phase " << phase_ms << " ms: max |error| " << max_abs(good.errors_us) << " us, restarts "
                           << good.restarts);
        CHECK(max_abs(good.errors_us) < 800);
        CHECK(good.restarts == 0);
    }
    // The same reads taken as arrivals: the line follows the read times, late by the phase
    // (and past half a period the clock restarts over and over).
    const LateReads fitted = read_on_tick(7.0, true);
    double mean = 0;
    for (double e : fitted.errors_us) mean += e;
    mean /= static_cast<double>(fitted.errors_us.size());
    INFO("read times fitted: mean error " << mean << " us, restarts " << fitted.restarts);
    CHECK((mean > 2'000 || fitted.restarts > 10));
}

TEST_CASE("A frame that vanished while reads were late is found out by the next prompt window")
{
    const LateReads r = read_on_tick(4.0, false, 3010);  // 30.1 s in, between two windows
    CHECK(r.restarts == 1);
    // Stamps after the restart (two windows later at most) are back on the grid.
    std::vector<double> last(r.errors_us.end() - 1000, r.errors_us.end());
    CHECK(max_abs(last) < 800);
}
