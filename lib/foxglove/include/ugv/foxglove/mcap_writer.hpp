// An MCAP writer (https://mcap.dev format, written by hand: Debian has no MCAP library).
//
// Chunked and indexed: messages go into chunks of about `chunk_size` uncompressed bytes,
// each followed by its message indexes; finish() writes the data end, the summary (schemas,
// channels, statistics, chunk indexes), summary offsets and the footer, all with CRCs. The
// writer does no I/O: every byte goes to a ByteSink, in file order, once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace ugv::foxglove {

class ByteSink
{
public:
    virtual ~ByteSink() = default;
    virtual void write(const uint8_t* data, std::size_t size) = 0;
};

// Collects everything in memory (tests, small files).
class VectorSink final : public ByteSink
{
public:
    void write(const uint8_t* data, std::size_t size) override { bytes.insert(bytes.end(), data, data + size); }
    std::vector<uint8_t> bytes;
};

enum class Compression { none, zstd, lz4 };

// "zstd", "lz4", "none" -> the compression; false for anything else.
bool parse_compression(std::string_view name, Compression& out);
// The levels the linked libzstd takes (negative ones are its fast levels).
int zstd_min_level();
int zstd_max_level();
// The compression's name in a chunk record ("" for none).
std::string_view compression_name(Compression c);

struct McapOptions
{
    Compression compression = Compression::zstd;
    std::size_t chunk_size = 4 << 20;  // uncompressed bytes per chunk before it is closed
    int zstd_level = 1;                // fast: the converter must run far faster than real time
    std::string profile;               // "" = no well-known profile
    std::string library = "ugv-mcap";
};

struct McapCounters
{
    uint64_t messages = 0;
    uint64_t chunks = 0;
    uint64_t uncompressed_bytes = 0;  // chunk records before compression
    uint64_t compressed_bytes = 0;    // chunk records as written
};

class McapWriter
{
public:
    // Writes the magic and the header at once.
    McapWriter(ByteSink& sink, McapOptions options);
    ~McapWriter();
    McapWriter(const McapWriter&) = delete;
    McapWriter& operator=(const McapWriter&) = delete;

    // Ids start at 1 (schema id 0 means "no schema" in MCAP).
    uint16_t add_schema(std::string_view name, std::string_view encoding, std::string_view data);
    uint16_t add_channel(uint16_t schema_id, std::string_view topic, std::string_view message_encoding,
                         const std::map<std::string, std::string>& metadata = {});
    // log_time and publish_time in ns since the epoch. The channel must have been added.
    void write_message(uint16_t channel_id, uint32_t sequence, uint64_t log_time, uint64_t publish_time,
                       const uint8_t* data, std::size_t size);
    // Closes the open chunk and writes the summary and the footer. Call once; nothing may be
    // written after it.
    void finish();

    const McapCounters& counters() const { return counters_; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    McapCounters counters_;
};

// CRC-32 (IEEE 802.3, as zlib computes it), the checksum MCAP uses.
// Folded with carry-less multiplications where the CPU has them (crc32.cpp).
uint32_t crc32(const uint8_t* data, std::size_t size, uint32_t crc = 0);
// zlib's, a word at a time: the reference crc32 is tested against.
uint32_t crc32_reference(const uint8_t* data, std::size_t size, uint32_t crc = 0);

}  // namespace ugv::foxglove
