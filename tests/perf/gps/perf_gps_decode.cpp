// Decode throughput of the NovAtel/NMEA stream on the real captures (bytes per second of
// input). Goal: >= 200 MB/s, i.e. far below 1 % of a core at any serial rate.
#include <benchmark/benchmark.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "ugv/novatel/checksum.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/interpreter.hpp"

namespace {

std::vector<uint8_t> load(const std::vector<std::string>& files)
{
    std::vector<uint8_t> all;
    for (const auto& f : files) {
        std::ifstream in(std::string(UGV_SHARED_DIR) + "/data/real/" + f, std::ios::binary);
        all.insert(all.end(), std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    return all;
}

const std::vector<uint8_t>& binary_capture()
{
    static const auto data = load({"ros-drivers-novatel_span_driver/propak6-sbas-fix.tcp-payload.bin",
                                   "gavlab-novatel/ParsingData.GPS", "rtklib/oemv_200911218.gps"});
    return data;
}

const std::vector<uint8_t>& text_capture()
{
    static const auto data = load({"gavlab-novatel/ParsingData.ASC", "swri-novatel_gps_driver/gpgga-gprmc-bestpos.udp-payload.bin",
                                   "gpsd-test-daemon/nmea-rtk.log"});
    return data;
}

void run_decoder(benchmark::State& state, const std::vector<uint8_t>& data, bool interpret)
{
    const std::size_t chunk = static_cast<std::size_t>(state.range(0));
    uint64_t messages = 0;
    for (auto _ : state) {
        ugv::novatel::Decoder d;
        ugv::novatel::Interpreter in;
        for (std::size_t i = 0; i < data.size(); i += chunk) {
            d.feed(data.data() + i, std::min(chunk, data.size() - i), 1'600'000'000'000'000LL,
                   [&](const ugv::novatel::Decoded& m) {
                       ++messages;
                       if (interpret) {
                           benchmark::DoNotOptimize(in.on_message(m.message, m.kind, m.arrival_utime, m.frame_bytes));
                       }
                   });
        }
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * data.size()));
    state.counters["messages"] = static_cast<double>(messages) / static_cast<double>(state.iterations());
}

void BM_DecodeBinary(benchmark::State& state) { run_decoder(state, binary_capture(), false); }
void BM_DecodeAndInterpretBinary(benchmark::State& state) { run_decoder(state, binary_capture(), true); }
void BM_DecodeTextAsciiNmea(benchmark::State& state) { run_decoder(state, text_capture(), false); }

void BM_Crc32(benchmark::State& state)
{
    const auto& data = binary_capture();
    for (auto _ : state) {
        benchmark::DoNotOptimize(ugv::novatel::crc32(data.data(), data.size()));
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * data.size()));
}

}  // namespace

BENCHMARK(BM_DecodeBinary)->Arg(64)->Arg(4096)->Arg(1 << 20);
BENCHMARK(BM_DecodeAndInterpretBinary)->Arg(4096);
BENCHMARK(BM_DecodeTextAsciiNmea)->Arg(64)->Arg(4096);
BENCHMARK(BM_Crc32);
