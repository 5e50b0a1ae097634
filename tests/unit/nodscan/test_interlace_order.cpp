// The interlacing order detector on synthetic nodding scans of flat ground: the right order
// leaves no zig-zag, a wrong one does, and the detector names the right one, whether the
// scans carry the right layout, a wrong one, or the linear timing.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "ugv/nodscan/interlace_order.hpp"

using namespace ugv::nodscan;

namespace {

constexpr double kTurnS = 1.0 / 75.0;

struct Synthetic
{
    int angle_deg = 180;
    double resolution_deg = 0.5;
    std::string true_order = "10";  // phase measured by each sweep
    std::string published = "true"; // "true", "linear", or an order the scans claim
};

int8_t digit(const std::string& s, std::size_t k) { return static_cast<int8_t>(s[k] - '0'); }

// 2 s of a laser 1 m above flat ground nodding between 0.25 and 0.75 rad at 0.5 rad/s (a
// triangle), servo at 100 Hz, range noise 3 mm; the scans' beams measured in interlaced
// sweeps in true_order, published with the given layout.
InterlaceResult detect(const Synthetic& s)
{
    const int sweeps = static_cast<int>(s.true_order.size());
    const int n = static_cast<int>(std::lround(s.angle_deg / s.resolution_deg)) + 1;
    const double step_s = s.resolution_deg / 360.0 * kTurnS;
    const double field_s = s.angle_deg / 360.0 * kTurnS;
    const auto tilt = [](double t) {
        const double u = std::fmod(0.5 * t, 1.0);  // a rise of 0.5 rad then a fall, 1 s each
        return 0.25 + 0.5 * (u < 0.5 ? 2.0 * u : 2.0 - 2.0 * u);
    };
    InterlaceConfig cfg;
    cfg.assembler.mount.axis_xyz_m = {0.0, 0.0, 1.0};
    InterlaceDetector d(cfg);
    std::mt19937 rng(7);
    std::normal_distribution<double> noise(0.0, 0.003);
    int next_servo_ms = 0;
    const double period_s = sweeps * kTurnS;
    for (int k = 0; k * period_s < 2.0; ++k) {
        const double start_s = 0.05 + k * period_s;
        const double last_beam_s = start_s + (sweeps - 1) * kTurnS + field_s;
        for (; next_servo_ms * 1e-3 <= last_beam_s + 0.01; ++next_servo_ms)
            d.add_servo({next_servo_ms * 1000, tilt(next_servo_ms * 1e-3)});
        std::vector<float> ranges(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) {
            int sweep = 0;
            for (int q = 0; q < sweeps; ++q)
                if (digit(s.true_order, static_cast<std::size_t>(q)) == i % sweeps) sweep = q;
            const double t = start_s + sweep * kTurnS + i * step_s;
            const double a = (-s.angle_deg / 2.0 + i * s.resolution_deg) * M_PI / 180.0;
            const double r = std::cos(a) > 0.05 ? 1.0 / (std::sin(tilt(t)) * std::cos(a)) : NAN;
            ranges[static_cast<std::size_t>(i)] = static_cast<float>(r + noise(rng));
        }
        ScanView v;
        v.angle_min = -s.angle_deg / 2.0 * M_PI / 180.0;
        v.angle_increment = s.resolution_deg * M_PI / 180.0;
        v.range_max = 80.0;
        v.ranges = ranges.data();
        v.n = ranges.size();
        if (s.published == "linear") {
            v.time_increment = period_s / (n - 1);
            v.utime = std::llround((last_beam_s - period_s) * 1e6);
        } else {
            const std::string& o = s.published == "true" ? s.true_order : s.published;
            std::vector<int8_t> order;
            for (std::size_t q = 0; q < o.size(); ++q) order.push_back(digit(o, q));
            REQUIRE(v.set_sweeps(order.data(), sweeps, kTurnS));
            v.time_increment = step_s;
            v.utime = std::llround(start_s * 1e6);
        }
        d.add_scan(v);
    }
    return d.finish();
}

double score(const InterlaceResult& r, const std::string& name)
{
    for (const OrderScore& s : r.candidates)
        if (s.name == name) return s.zigzag_rms_m;
    FAIL("no candidate " << name);
    return NAN;
}

std::string best(const InterlaceResult& r) { return r.best < 0 ? "" : r.candidates[static_cast<std::size_t>(r.best)].name; }

}  // namespace

TEST_CASE("interlace detector: 0.5 deg, the right order has no zig-zag and is named")
{
    for (const std::string order : {"01", "10"}) {
        Synthetic s;
        s.true_order = order;
        const InterlaceResult r = detect(s);
        const std::string wrong = order == "01" ? "10" : "01";
        CHECK(r.scans >= 70);
        // Published with the right layout: the points are as smooth as the noise allows.
        CHECK(score(r, "as published") < 0.003);
        CHECK(score(r, order) < 0.003);
        // The wrong order: every other beam a sweep (13.3 ms, 6.7 mrad of tilt) off.
        CHECK(score(r, wrong) > 3.0 * score(r, order));
        CHECK(best(r) == order);
        CHECK(r.margin() > 3.0);
    }
}

TEST_CASE("interlace detector: scans published with the wrong or the linear timing zig-zag, and still name the right order")
{
    Synthetic s;
    s.true_order = "10";
    s.published = "01";
    InterlaceResult r = detect(s);
    CHECK(score(r, "as published") > 3.0 * score(r, "10"));
    CHECK(best(r) == "10");
    s.published = "linear";
    r = detect(s);
    CHECK(score(r, "as published") > 3.0 * score(r, "10"));
    CHECK(best(r) == "10");
}

TEST_CASE("interlace detector: 0.25 deg over 100 deg, four sweeps, one of 24 orders")
{
    Synthetic s;
    s.angle_deg = 100;
    s.resolution_deg = 0.25;
    s.true_order = "2031";
    s.published = "linear";
    const InterlaceResult r = detect(s);
    CHECK(r.candidates.size() == 25);
    CHECK(best(r) == "2031");
    CHECK(r.margin() > 1.5);
    CHECK(score(r, "as published") > 3.0 * score(r, "2031"));
}

TEST_CASE("interlace detector: without a nod no order can be told")
{
    InterlaceDetector d;
    d.add_servo({0, 0.3});
    d.add_servo({100'000, 0.3});
    std::vector<float> ranges(361, 3.0f);
    ScanView v;
    v.utime = 10'000;
    v.angle_min = -M_PI / 2;
    v.angle_increment = 0.5 * M_PI / 180.0;
    v.time_increment = 0.0001;
    v.range_max = 80.0;
    v.ranges = ranges.data();
    v.n = ranges.size();
    d.add_scan(v);
    const InterlaceResult r = d.finish();
    CHECK(r.scans == 1);
    CHECK(r.margin() == Approx(1.0));
}
