// Decode throughput of the 3DM-GX1 codec: framing alone, framing through garbage, and the
// whole path per sample (frame -> scaled sample -> body/ENU measurement -> stamp).
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "ugv/io/device_clock_filter.hpp"
#include "ugv/microstrain_gx1/frame_parser.hpp"
#include "ugv/microstrain_gx1/orientation.hpp"
#include "ugv/microstrain_gx1/scaling.hpp"

using namespace ugv::microstrain_gx1;

namespace {

std::vector<uint8_t> stream_of(uint8_t command, std::size_t frames, double garbage_fraction)
{
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<uint8_t> out;
    const std::size_t words = reply_words(command);
    for (std::size_t k = 0; k < frames; ++k) {
        std::vector<uint16_t> w(words);
        for (auto& x : w) x = static_cast<uint16_t>(byte(rng) << 8 | byte(rng));
        w.back() = static_cast<uint16_t>(k);
        const auto f = encode_reply(command, w);
        out.insert(out.end(), f.begin(), f.end());
        if (unit(rng) < garbage_fraction)
            for (int i = 0; i < 10; ++i) out.push_back(i % 3 == 0 ? command : static_cast<uint8_t>(byte(rng)));
    }
    return out;
}

void run_parser(benchmark::State& state, uint8_t command, double garbage)
{
    const auto bytes = stream_of(command, 10000, garbage);
    std::size_t frames = 0;
    for (auto _ : state) {
        FrameParser p;
        p.accept_only({command});
        Frame f;
        for (std::size_t at = 0; at < bytes.size(); at += 64) {
            p.feed(bytes.data() + at, std::min<std::size_t>(64, bytes.size() - at));
            while (p.next(f)) ++frames;
        }
        benchmark::DoNotOptimize(f);
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * bytes.size()));
    state.counters["frames/s"] = benchmark::Counter(static_cast<double>(frames), benchmark::Counter::kIsRate);
}

void BM_parse_0x31_clean(benchmark::State& s) { run_parser(s, 0x31, 0.0); }
void BM_parse_0x31_garbage10pct(benchmark::State& s) { run_parser(s, 0x31, 0.1); }
void BM_parse_0x0C_clean(benchmark::State& s) { run_parser(s, 0x0C, 0.0); }

void BM_decode_convert_stamp_0x31(benchmark::State& state)
{
    const auto bytes = encode_reply(0x31, {1820, static_cast<uint16_t>(-910), 16384, 10, 20, static_cast<uint16_t>(-3855), 30, 40, 50, 0});
    FrameParser p;
    p.feed(bytes.data(), bytes.size());
    Frame f;
    p.next(f);
    const GainScales g;
    const FrameConverter conv(rotation_from_euler(0.01, 0.02, 0.03), 0.1);
    ugv::io::DeviceClockFilter clock;
    double t = 0;
    for (auto _ : state) {
        const DeviceSample s = decode_sample(f, g);
        const Measurement m = conv.convert(s);
        t += 0.01;
        benchmark::DoNotOptimize(clock.update(t, static_cast<int64_t>(t * 1e6) + 1000));
        benchmark::DoNotOptimize(m);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

}  // namespace

BENCHMARK(BM_parse_0x31_clean);
BENCHMARK(BM_parse_0x31_garbage10pct);
BENCHMARK(BM_parse_0x0C_clean);
BENCHMARK(BM_decode_convert_stamp_0x31);
