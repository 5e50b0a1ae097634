// The MCAP record encoder against the format's byte layout: magic, header, footer, the
// records of a chunk and the summary that indexes them, CRCs recomputed independently.
#include <catch2/catch.hpp>

#include <lz4frame.h>
#include <zstd.h>

#include <cstring>
#include <map>

#include "ugv/foxglove/mcap_writer.hpp"

using namespace ugv::foxglove;

namespace {

const uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

uint64_t le(const std::vector<uint8_t>& b, std::size_t at, int bytes)
{
    REQUIRE(at + static_cast<std::size_t>(bytes) <= b.size());
    uint64_t v = 0;
    for (int k = bytes - 1; k >= 0; --k) v = (v << 8) | b[at + static_cast<std::size_t>(k)];
    return v;
}

std::string str(const std::vector<uint8_t>& b, std::size_t& at)
{
    const auto n = static_cast<std::size_t>(le(b, at, 4));
    std::string s(b.begin() + static_cast<long>(at + 4), b.begin() + static_cast<long>(at + 4 + n));
    at += 4 + n;
    return s;
}

struct Record
{
    uint8_t opcode;
    std::size_t offset;   // of the opcode
    std::size_t content;  // of the content
    std::size_t length;   // of the content
};

// The records between the leading and trailing magic, each checked to end inside the file.
std::vector<Record> records(const std::vector<uint8_t>& b, std::size_t from, std::size_t to)
{
    std::vector<Record> out;
    std::size_t at = from;
    while (at < to) {
        REQUIRE(at + 9 <= to);
        Record r{b[at], at, at + 9, static_cast<std::size_t>(le(b, at + 1, 8))};
        REQUIRE(r.content + r.length <= to);
        out.push_back(r);
        at = r.content + r.length;
    }
    REQUIRE(at == to);
    return out;
}

std::vector<uint8_t> sample_file(Compression c, std::size_t chunk_size = 1 << 20)
{
    VectorSink sink;
    McapOptions o;
    o.compression = c;
    o.chunk_size = chunk_size;
    McapWriter w(sink, o);
    const uint16_t s = w.add_schema("ugv.pose_t", "jsonschema", "{}");
    const uint16_t a = w.add_channel(s, "POSE", "json");
    const uint16_t b = w.add_channel(s, "POSE2", "json", {{"k", "v"}});
    const std::string m1 = "{\"a\":1}", m2 = "{\"b\":22}";
    w.write_message(a, 0, 2000, 2000, reinterpret_cast<const uint8_t*>(m1.data()), m1.size());
    w.write_message(b, 0, 1000, 1500, reinterpret_cast<const uint8_t*>(m2.data()), m2.size());
    w.write_message(a, 1, 3000, 3000, reinterpret_cast<const uint8_t*>(m1.data()), m1.size());
    w.finish();
    return sink.bytes;
}

}  // namespace

TEST_CASE("crc32 is the IEEE CRC-32 (check value of \"123456789\")")
{
    const std::string s = "123456789";
    CHECK(crc32(reinterpret_cast<const uint8_t*>(s.data()), s.size()) == 0xCBF43926u);
    // Incremental: the CRC of a whole equals the CRC continued over its parts.
    const uint32_t part = crc32(reinterpret_cast<const uint8_t*>(s.data()), 4);
    CHECK(crc32(reinterpret_cast<const uint8_t*>(s.data()) + 4, 5, part) == 0xCBF43926u);
}

TEST_CASE("crc32 equals zlib's at every length, alignment and starting value")
{
    // 4100 bytes: several 64-byte folds, the 16-byte tail loop and the ragged end.
    std::vector<uint8_t> bytes(4100);
    uint32_t x = 0x12345678u;
    for (auto& b : bytes) {
        x = x * 1664525u + 1013904223u;
        b = static_cast<uint8_t>(x >> 24);
    }
    for (const uint32_t start : {0u, 0xFFFFFFFFu, 0xCBF43926u}) {
        for (std::size_t offset = 0; offset < 16; offset += 5) {
            for (std::size_t size = 0; size <= 300; ++size) {
                INFO("start " << start << " offset " << offset << " size " << size);
                REQUIRE(crc32(bytes.data() + offset, size, start) == crc32_reference(bytes.data() + offset, size, start));
            }
            REQUIRE(crc32(bytes.data() + offset, 4000, start) == crc32_reference(bytes.data() + offset, 4000, start));
        }
    }
    // A buffer of 0xFF and one of zeros: the folds' carries and the empty polynomial.
    const std::vector<uint8_t> ones(1024, 0xFF), zeros(1024, 0);
    CHECK(crc32(ones.data(), ones.size()) == crc32_reference(ones.data(), ones.size()));
    CHECK(crc32(zeros.data(), zeros.size()) == crc32_reference(zeros.data(), zeros.size()));
}

TEST_CASE("an empty file: magic, header, data end, summary, footer, magic")
{
    VectorSink sink;
    McapOptions o;
    o.library = "lib";
    McapWriter w(sink, o);
    w.finish();
    const auto& b = sink.bytes;
    REQUIRE(b.size() > 16);
    CHECK(std::memcmp(b.data(), kMagic, 8) == 0);
    CHECK(std::memcmp(b.data() + b.size() - 8, kMagic, 8) == 0);
    // Header: opcode 1, length 4 + 0 + 4 + 3, profile "", library "lib".
    const std::vector<uint8_t> header = {0x01, 11, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 3, 0, 0, 0, 'l', 'i', 'b'};
    CHECK(std::vector<uint8_t>(b.begin() + 8, b.begin() + 28) == header);
    // Data end right after: opcode 0x0f, length 4, the CRC of the 28 bytes before it.
    CHECK(b[28] == 0x0f);
    CHECK(le(b, 29, 8) == 4);
    CHECK(le(b, 37, 4) == crc32(b.data(), 28));
    // Footer: the last record, 20 bytes of content, before the magic.
    const std::size_t footer = b.size() - 8 - 29;
    CHECK(b[footer] == 0x02);
    CHECK(le(b, footer + 1, 8) == 20);
    const auto summary_start = static_cast<std::size_t>(le(b, footer + 9, 8));
    const auto offsets_start = static_cast<std::size_t>(le(b, footer + 17, 8));
    CHECK(summary_start == 41);
    CHECK(le(b, footer + 25, 4) == crc32(b.data() + summary_start, footer + 25 - summary_start));
    // The summary holds the statistics alone: 0 messages, 0 chunks.
    const auto summary = records(b, summary_start, offsets_start);
    REQUIRE(summary.size() == 1);
    CHECK(summary[0].opcode == 0x0b);
    CHECK(le(b, summary[0].content, 8) == 0);
    const auto offsets = records(b, offsets_start, footer);
    REQUIRE(offsets.size() == 1);
    CHECK(b[offsets[0].content] == 0x0b);
    CHECK(le(b, offsets[0].content + 1, 8) == summary_start);
}

TEST_CASE("messages go into a chunk, indexed by message indexes, a chunk index and statistics")
{
    const auto b = sample_file(Compression::none);
    const std::size_t footer = b.size() - 8 - 29;
    const auto summary_start = static_cast<std::size_t>(le(b, footer + 9, 8));
    const auto data = records(b, 8, summary_start);
    // header, schema, 2 channels, chunk, 2 message indexes, data end
    std::vector<uint8_t> ops;
    for (const auto& r : data) ops.push_back(r.opcode);
    REQUIRE(ops == std::vector<uint8_t>{0x01, 0x03, 0x04, 0x04, 0x06, 0x07, 0x07, 0x0f});
    CHECK(le(b, data.back().content, 4) == crc32(b.data(), data.back().offset));

    // Channel 2: id, schema id, topic, encoding, metadata {k: v}.
    std::size_t at = data[3].content;
    CHECK(le(b, at, 2) == 2);
    CHECK(le(b, at + 2, 2) == 1);
    at += 4;
    CHECK(str(b, at) == "POSE2");
    CHECK(str(b, at) == "json");
    CHECK(le(b, at, 4) == 4 + 1 + 4 + 1);
    at += 4;
    CHECK(str(b, at) == "k");
    CHECK(str(b, at) == "v");

    const Record& chunk = data[4];
    at = chunk.content;
    CHECK(le(b, at, 8) == 1000);       // message start time
    CHECK(le(b, at + 8, 8) == 3000);   // message end time
    const auto uncompressed = static_cast<std::size_t>(le(b, at + 16, 8));
    const auto chunk_crc = static_cast<uint32_t>(le(b, at + 24, 4));
    at += 28;
    CHECK(str(b, at) == "");
    CHECK(le(b, at, 8) == uncompressed);
    const std::size_t inner = at + 8;
    CHECK(crc32(b.data() + inner, uncompressed) == chunk_crc);
    const auto msgs = records(b, inner, inner + uncompressed);
    REQUIRE(msgs.size() == 3);
    // The second message: channel 2, sequence 0, log time 1000, publish time 1500, its bytes.
    at = msgs[1].content;
    CHECK(le(b, at, 2) == 2);
    CHECK(le(b, at + 2, 4) == 0);
    CHECK(le(b, at + 6, 8) == 1000);
    CHECK(le(b, at + 14, 8) == 1500);
    CHECK(std::string(b.begin() + static_cast<long>(at + 22), b.begin() + static_cast<long>(msgs[1].content + msgs[1].length)) ==
          "{\"b\":22}");

    // Message index of channel 1: (2000, offset of message 0), (3000, offset of message 2).
    at = data[5].content;
    CHECK(le(b, at, 2) == 1);
    CHECK(le(b, at + 2, 4) == 32);
    CHECK(le(b, at + 6, 8) == 2000);
    CHECK(le(b, at + 14, 8) == msgs[0].offset - inner);
    CHECK(le(b, at + 22, 8) == 3000);
    CHECK(le(b, at + 30, 8) == msgs[2].offset - inner);

    // Summary: schema, 2 channels, statistics, chunk index.
    const auto offsets_start = static_cast<std::size_t>(le(b, footer + 17, 8));
    const auto summary = records(b, summary_start, offsets_start);
    ops.clear();
    for (const auto& r : summary) ops.push_back(r.opcode);
    REQUIRE(ops == std::vector<uint8_t>{0x03, 0x04, 0x04, 0x0b, 0x08});
    at = summary[3].content;
    CHECK(le(b, at, 8) == 3);        // messages
    CHECK(le(b, at + 8, 2) == 1);    // schemas
    CHECK(le(b, at + 10, 4) == 2);   // channels
    CHECK(le(b, at + 22, 4) == 1);   // chunks
    CHECK(le(b, at + 26, 8) == 1000);
    CHECK(le(b, at + 34, 8) == 3000);
    CHECK(le(b, at + 42, 4) == 20);  // two (channel, count) pairs
    CHECK(le(b, at + 46, 2) == 1);
    CHECK(le(b, at + 48, 8) == 2);
    CHECK(le(b, at + 56, 2) == 2);
    CHECK(le(b, at + 58, 8) == 1);
    at = summary[4].content;
    CHECK(le(b, at + 16, 8) == chunk.offset);
    CHECK(le(b, at + 24, 8) == chunk.content + chunk.length - chunk.offset);
    CHECK(le(b, at + 32, 4) == 20);
    CHECK(le(b, at + 36, 2) == 1);
    CHECK(le(b, at + 38, 8) == data[5].offset);
    CHECK(le(b, at + 46, 2) == 2);
    CHECK(le(b, at + 48, 8) == data[6].offset);
    CHECK(le(b, at + 56, 8) == data[7].offset - data[5].offset);  // message index length
    // Summary offsets: one per group, each pointing at its first record.
    const auto offsets = records(b, offsets_start, footer);
    REQUIRE(offsets.size() == 4);
    for (const auto& r : offsets) {
        const auto start = static_cast<std::size_t>(le(b, r.content + 1, 8));
        CHECK(b[start] == b[r.content]);
    }
}

TEST_CASE("zstd and lz4 chunks decompress to the uncompressed chunk's records")
{
    const auto plain = sample_file(Compression::none);
    auto chunk_records = [](const std::vector<uint8_t>& b, std::string& compression, std::size_t& uncompressed) {
        std::size_t at = 8;
        for (;;) {
            REQUIRE(at + 9 <= b.size());
            if (b[at] == 0x06) break;
            at += 9 + static_cast<std::size_t>(le(b, at + 1, 8));
        }
        at += 9;
        uncompressed = static_cast<std::size_t>(le(b, at + 16, 8));
        at += 28;
        compression = str(b, at);
        const auto n = static_cast<std::size_t>(le(b, at, 8));
        return std::vector<uint8_t>(b.begin() + static_cast<long>(at + 8), b.begin() + static_cast<long>(at + 8 + n));
    };
    std::string c;
    std::size_t n = 0;
    const auto want = chunk_records(plain, c, n);
    CHECK(c.empty());

    const auto z = chunk_records(sample_file(Compression::zstd), c, n);
    CHECK(c == "zstd");
    std::vector<uint8_t> out(n);
    CHECK(ZSTD_decompress(out.data(), out.size(), z.data(), z.size()) == n);
    CHECK(out == want);

    const auto l = chunk_records(sample_file(Compression::lz4), c, n);
    CHECK(c == "lz4");
    LZ4F_dctx* dctx = nullptr;
    REQUIRE(!LZ4F_isError(LZ4F_createDecompressionContext(&dctx, LZ4F_VERSION)));
    std::size_t dst = n, src = l.size();
    std::fill(out.begin(), out.end(), 0);
    CHECK(LZ4F_decompress(dctx, out.data(), &dst, l.data(), &src, nullptr) == 0);
    LZ4F_freeDecompressionContext(dctx);
    CHECK(dst == n);
    CHECK(out == want);
}

TEST_CASE("a small chunk size closes a chunk per message")
{
    const auto b = sample_file(Compression::none, 1);
    int chunks = 0, indexes = 0;
    std::size_t at = 8;
    while (at + 9 <= b.size() - 8) {
        chunks += b[at] == 0x06;
        indexes += b[at] == 0x08;
        at += 9 + static_cast<std::size_t>(le(b, at + 1, 8));
    }
    CHECK(chunks == 3);
    CHECK(indexes == 3);
}

TEST_CASE("misuse is refused")
{
    VectorSink sink;
    McapWriter w(sink, {});
    CHECK_THROWS_AS(w.add_channel(1, "X", "json"), std::invalid_argument);
    const uint8_t byte = 0;
    CHECK_THROWS_AS(w.write_message(1, 0, 0, 0, &byte, 1), std::invalid_argument);
    Compression c;
    CHECK(parse_compression("lz4", c));
    CHECK(c == Compression::lz4);
    CHECK_FALSE(parse_compression("gzip", c));
}
