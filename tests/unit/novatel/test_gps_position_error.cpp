// The simulated receiver's "markov" position error (tools/sim/gps/position_error.cpp): its
// spread and correlation time from long sequences, the jump when the position type changes,
// and the receiver reporting the sigma its errors have.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "capture_file.hpp"
#include "gps_emulator.hpp"
#include "position_error.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/enums.hpp"

using namespace ugv::sim::gps;
namespace nv = ugv::novatel;

namespace {

constexpr int64_t kStart = 1'700'000'000'000'000LL;

}  // namespace

TEST_CASE("markov GPS error: the spread and correlation time of a long sequence are the configured ones")
{
    // RTK float: sigma 0.15 m, tau 60 s, sampled every 12 s (rho = exp(-0.2)) 100000 times.
    // Effective samples N (1 - rho) / (1 + rho) = 10^4: the variance's relative standard
    // error is 1.4 % (tolerance 6 %); rho's standard error sqrt((1 - rho^2) / N) = 0.0018
    // gives tau within 1.1 % (tolerance 5 %).
    PositionErrorConfig c;
    c.seed = 7;
    PositionErrorModel m(c);
    const double dt = 12.0, sigma = 0.15, tau = 60.0;
    const int n = 100000;
    double s2[3] = {0, 0, 0}, lag[3] = {0, 0, 0}, prev[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const Ned3 e = m.at(kStart + static_cast<int64_t>(i * dt * 1e6), nv::position_type::l1_float);
        const double v[3] = {e.north_m, e.east_m, e.up_m};
        for (int k = 0; k < 3; ++k) {
            s2[k] += v[k] * v[k];
            if (i > 0) lag[k] += v[k] * prev[k];
            prev[k] = v[k];
        }
    }
    for (int k = 0; k < 3; ++k) {
        const double scale = k == 2 ? 1.5 : 1.0;
        const double var = s2[k] / n, rho = lag[k] / (n - 1) / var;
        INFO("axis " << k << ": sigma " << std::sqrt(var) << " m, tau " << -dt / std::log(rho) << " s");
        CHECK(var == Approx(std::pow(scale * sigma, 2)).epsilon(0.06));
        CHECK(-dt / std::log(rho) == Approx(tau).epsilon(0.05));
    }
    CHECK(m.sigma_horizontal_m(nv::position_type::l1_float) == Approx(sigma));
    CHECK(m.sigma_height_m(nv::position_type::l1_float) == Approx(1.5 * sigma));
}

TEST_CASE("markov GPS error: a change of position type jumps; back, the old class's error resumes")
{
    // RTK fixed (2 cm, 30 s) at 1 Hz for 10 s, DGPS (0.4 m) for 5 s, fixed again. Over 2000
    // seeds: the step into DGPS has the spread of two independent errors, sqrt(0.02^2 +
    // 0.4^2) (relative standard error 1.1 %, tolerance 6 %), a step within fixed is
    // sqrt(2 (1 - exp(-1/30))) x 2 cm = 0.5 cm; back in fixed after 6 s the error is
    // correlated exp(-6/30) = 0.82 with the one before (standard error 0.008; tolerance 0.04).
    double jump2 = 0, step2 = 0, before2 = 0, back2 = 0, cross = 0;
    const int seeds = 2000;
    for (int s = 1; s <= seeds; ++s) {
        PositionErrorConfig c;
        c.seed = static_cast<uint32_t>(s);
        PositionErrorModel m(c);
        Ned3 e9{}, e10{}, e11{}, e16{};
        for (int t = 0; t <= 16; ++t) {
            const uint32_t type = t <= 10 || t == 16 ? nv::position_type::narrow_int : nv::position_type::psrdiff;
            const Ned3 e = m.at(kStart + t * 1'000'000LL, type);
            if (t == 9) e9 = e;
            if (t == 10) e10 = e;
            if (t == 11) e11 = e;
            if (t == 16) e16 = e;
        }
        jump2 += std::pow(e11.north_m - e10.north_m, 2) + std::pow(e11.east_m - e10.east_m, 2);
        step2 += std::pow(e10.north_m - e9.north_m, 2) + std::pow(e10.east_m - e9.east_m, 2);
        before2 += e10.north_m * e10.north_m + e10.east_m * e10.east_m;
        back2 += e16.north_m * e16.north_m + e16.east_m * e16.east_m;
        cross += e10.north_m * e16.north_m + e10.east_m * e16.east_m;
    }
    CHECK(std::sqrt(jump2 / (2 * seeds)) == Approx(std::hypot(0.02, 0.4)).epsilon(0.06));
    CHECK(std::sqrt(step2 / (2 * seeds)) == Approx(std::sqrt(2 * (1 - std::exp(-1.0 / 30))) * 0.02).epsilon(0.06));
    CHECK(cross / std::sqrt(before2 * back2) == Approx(std::exp(-6.0 / 30)).margin(0.04));
}

TEST_CASE("markov GPS error in the receiver: BESTPOS reports the sigma its errors have")
{
    // Stationary at 1 Hz, the type changing every 200 s among fixed, float and DGPS, the time
    // constants 0.5 s (fixes nearly independent): the errors divided by the reported sigma
    // have a mean square of 1 (6000 fixes x 2 axes; standard error 2 %, tolerance 8 %).
    EmulatorConfig c;
    c.noise_scale = 2.0;  // the reported sigma scales with the errors
    PositionErrorConfig m;
    for (auto& k : m.classes) k.time_constant_s = 0.5;
    m.seed = 3;
    c.markov = m;
    c.script = parse_script("NARROW_INT@0,L1_FLOAT@200,PSRDIFF@400,NARROW_INT@600,L1_FLOAT@800,PSRDIFF@1000");
    GpsEmulator e(c, kStart);
    const std::string log = "LOG BESTPOSB ONTIME 0.2\r\n";
    e.on_host_bytes(reinterpret_cast<const uint8_t*>(log.data()), log.size());
    nv::Decoder d;
    double sum2 = 0;
    int n = 0, jumps_seen = 0;
    double last_sigma = 0;
    for (int64_t t = kStart; t <= kStart + 1'200'000'000LL; t += 200'000) {
        const std::string out = e.tick(t);
        const auto b = ugv::novatel::test::bytes(out);
        d.feed(b.data(), b.size(), 0, [&](const nv::Decoded& msg) {
            const auto* p = std::get_if<nv::Position>(&msg.message);
            if (p == nullptr) return;
            const double north = (p->latitude_deg - c.latitude_deg) * 3.14159265358979323846 / 180 * 6378137.0;
            const double east = (p->longitude_deg - c.longitude_deg) * 3.14159265358979323846 / 180 * 6378137.0 *
                                std::cos(c.latitude_deg * 3.14159265358979323846 / 180);
            sum2 += std::pow(north / p->sigma_latitude_m, 2) + std::pow(east / p->sigma_longitude_m, 2);
            n += 2;
            CHECK(p->sigma_height_m == Approx(1.5 * p->sigma_latitude_m));
            if (p->sigma_latitude_m != last_sigma) ++jumps_seen;
            last_sigma = p->sigma_latitude_m;
        });
    }
    REQUIRE(n > 11000);
    CHECK(jumps_seen == 6);  // the first fix and five changes of type
    CHECK(sum2 / n == Approx(1.0).epsilon(0.08));
}
