// Throughput of the SICK LMS 2xx codec: CRC, telegram framing and scan decoding, on a
// stream of 361-value scans fed in 4 KiB chunks (goal: >= 200 MB/s). Reported, not asserted.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "ugv/sick_lms2xx/crc.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"
#include "ugv/sick_lms2xx/scan.hpp"

using namespace ugv::sick_lms2xx;

namespace {

std::vector<uint8_t> scan_stream(int scans, bool garbage)
{
    std::mt19937 rng(42);
    std::uniform_int_distribution<int> byte(0, 255), len(0, 40);
    std::vector<uint8_t> s;
    for (int k = 0; k < scans; ++k) {
        std::vector<uint16_t> values(361);
        for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<uint16_t>((i * 13 + k * 7) % 8190);
        if (garbage)
            for (int g = len(rng); g > 0; --g) s.push_back(static_cast<uint8_t>(byte(rng)));
        const auto t = encode_scan_telegram(values, Units::mm, 0, -1, 0x10);
        s.insert(s.end(), t.begin(), t.end());
    }
    return s;
}

void decode_stream(benchmark::State& state, bool garbage)
{
    const std::vector<uint8_t> stream = scan_stream(200, garbage);
    Decoder dec;
    Scan scan;
    int64_t scans = 0;
    const auto handler = [&](const DecoderEvent& ev) {
        if (ev.kind == DecoderEvent::Kind::telegram && decode_scan(ev.telegram, scan) == ScanError::none) ++scans;
    };
    for (auto _ : state) {
        for (std::size_t at = 0; at < stream.size(); at += 4096) {
            const std::size_t n = std::min<std::size_t>(4096, stream.size() - at);
            dec.feed(stream.data() + at, n, handler);
        }
        benchmark::DoNotOptimize(scans);
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(stream.size()));
    state.counters["scans/s"] = benchmark::Counter(static_cast<double>(scans), benchmark::Counter::kIsRate);
}

void BM_DecodeScanStream(benchmark::State& state) { decode_stream(state, false); }
void BM_DecodeScanStreamWithGarbage(benchmark::State& state) { decode_stream(state, true); }

void BM_Crc16(benchmark::State& state)
{
    const std::vector<uint8_t> t = scan_stream(1, false);
    for (auto _ : state) benchmark::DoNotOptimize(crc16(t.data(), t.size() - 2));
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(t.size() - 2));
}

}  // namespace

BENCHMARK(BM_DecodeScanStream);
BENCHMARK(BM_DecodeScanStreamWithGarbage);
BENCHMARK(BM_Crc16);
