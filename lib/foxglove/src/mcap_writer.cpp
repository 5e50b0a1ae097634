#include "ugv/foxglove/mcap_writer.hpp"

#include <lz4frame.h>
#include <zstd.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace ugv::foxglove {
namespace {

constexpr uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum Opcode : uint8_t {
    op_header = 0x01,
    op_footer = 0x02,
    op_schema = 0x03,
    op_channel = 0x04,
    op_message = 0x05,
    op_chunk = 0x06,
    op_message_index = 0x07,
    op_chunk_index = 0x08,
    op_statistics = 0x0b,
    op_summary_offset = 0x0e,
    op_data_end = 0x0f,
};

// Little-endian primitives into a byte vector: MCAP's encoding.
void put_u8(std::vector<uint8_t>& b, uint8_t v) { b.push_back(v); }
template <typename T>
void put_le(std::vector<uint8_t>& b, T v)
{
    for (std::size_t k = 0; k < sizeof(T); ++k) b.push_back(static_cast<uint8_t>(static_cast<uint64_t>(v) >> (8 * k)));
}
void put_u16(std::vector<uint8_t>& b, uint16_t v) { put_le(b, v); }
void put_u32(std::vector<uint8_t>& b, uint32_t v) { put_le(b, v); }
void put_u64(std::vector<uint8_t>& b, uint64_t v) { put_le(b, v); }
void put_bytes(std::vector<uint8_t>& b, const void* p, std::size_t n)
{
    const auto* c = static_cast<const uint8_t*>(p);
    b.insert(b.end(), c, c + n);
}
uint32_t checked_u32(std::size_t n, const char* what)
{
    if (n > std::numeric_limits<uint32_t>::max()) throw std::length_error(std::string("mcap: ") + what + " longer than 4 GiB");
    return static_cast<uint32_t>(n);
}
// A string: uint32 length, then the bytes.
void put_string(std::vector<uint8_t>& b, std::string_view s)
{
    put_u32(b, checked_u32(s.size(), "string"));
    put_bytes(b, s.data(), s.size());
}

// A record: opcode, uint64 content length, content.
void put_record(std::vector<uint8_t>& b, uint8_t opcode, const std::vector<uint8_t>& content)
{
    put_u8(b, opcode);
    put_u64(b, content.size());
    put_bytes(b, content.data(), content.size());
}

struct ChunkIndexEntry
{
    uint64_t start_time = 0, end_time = 0;
    uint64_t chunk_offset = 0, chunk_length = 0;
    std::vector<std::pair<uint16_t, uint64_t>> message_index_offsets;
    uint64_t message_index_length = 0;
    uint64_t compressed_size = 0, uncompressed_size = 0;
};

}  // namespace

bool parse_compression(std::string_view name, Compression& out)
{
    if (name == "zstd") out = Compression::zstd;
    else if (name == "lz4") out = Compression::lz4;
    else if (name == "none") out = Compression::none;
    else return false;
    return true;
}

int zstd_min_level() { return ZSTD_minCLevel(); }
int zstd_max_level() { return ZSTD_maxCLevel(); }

std::string_view compression_name(Compression c)
{
    switch (c) {
    case Compression::zstd: return "zstd";
    case Compression::lz4: return "lz4";
    case Compression::none: break;
    }
    return "";
}

struct McapWriter::Impl
{
    ByteSink& sink;
    McapOptions options;
    uint64_t offset = 0;        // bytes written so far
    uint32_t data_crc = 0;      // of the data section, up to the data end record
    bool finished = false;

    std::vector<std::vector<uint8_t>> schema_records, channel_records;  // each a whole record, for the summary
    std::vector<uint64_t> channel_counts;                               // by channel id - 1
    uint64_t message_count = 0, start_time = 0, end_time = 0;

    // The open chunk: its records uncompressed, its time span, and per channel the
    // (log time, offset in the chunk) of each message.
    std::vector<uint8_t> chunk;
    uint64_t chunk_start = 0, chunk_end = 0;
    std::vector<std::vector<std::pair<uint64_t, uint64_t>>> chunk_index;  // by channel id - 1
    std::vector<ChunkIndexEntry> chunk_indexes;

    std::vector<uint8_t> scratch, compressed;
    ZSTD_CCtx* zstd = nullptr;

    Impl(ByteSink& s, McapOptions o) : sink(s), options(std::move(o)) {}
    ~Impl() { ZSTD_freeCCtx(zstd); }

    void emit(const std::vector<uint8_t>& b, bool data_section = true) { emit(b.data(), b.size(), data_section); }
    void emit(const uint8_t* p, std::size_t n, bool data_section = true)
    {
        if (n == 0) return;
        sink.write(p, n);
        if (data_section) data_crc = crc32(p, n, data_crc);
        offset += n;
    }

    // A schema or channel record: written now, kept for the summary.
    std::vector<uint8_t> definition(uint8_t opcode, const std::vector<uint8_t>& content)
    {
        std::vector<uint8_t> record;
        put_record(record, opcode, content);
        emit(record);
        return record;
    }

    const uint8_t* compress(std::size_t& size)
    {
        switch (options.compression) {
        case Compression::none:
            size = chunk.size();
            return chunk.data();
        case Compression::zstd: {
            if (!zstd) zstd = ZSTD_createCCtx();
            if (!zstd) throw std::runtime_error("mcap: zstd: cannot create a context");
            compressed.resize(ZSTD_compressBound(chunk.size()));
            const std::size_t n = ZSTD_compressCCtx(zstd, compressed.data(), compressed.size(), chunk.data(), chunk.size(),
                                                    options.zstd_level);
            if (ZSTD_isError(n)) throw std::runtime_error(std::string("mcap: zstd: ") + ZSTD_getErrorName(n));
            size = n;
            return compressed.data();
        }
        case Compression::lz4: {
            LZ4F_preferences_t prefs{};
            prefs.frameInfo.contentSize = chunk.size();
            compressed.resize(LZ4F_compressFrameBound(chunk.size(), &prefs));
            const std::size_t n = LZ4F_compressFrame(compressed.data(), compressed.size(), chunk.data(), chunk.size(), &prefs);
            if (LZ4F_isError(n)) throw std::runtime_error(std::string("mcap: lz4: ") + LZ4F_getErrorName(n));
            size = n;
            return compressed.data();
        }
        }
        size = 0;
        return nullptr;
    }

    void close_chunk(McapCounters& counters)
    {
        if (chunk.empty()) return;
        ChunkIndexEntry entry;
        entry.start_time = chunk_start;
        entry.end_time = chunk_end;
        entry.chunk_offset = offset;
        entry.uncompressed_size = chunk.size();
        const uint32_t chunk_crc = crc32(chunk.data(), chunk.size());
        std::size_t csize = 0;
        const uint8_t* cdata = compress(csize);
        entry.compressed_size = csize;
        const std::string_view cname = compression_name(options.compression);

        scratch.clear();
        put_u8(scratch, op_chunk);
        put_u64(scratch, 8 + 8 + 8 + 4 + 4 + cname.size() + 8 + csize);
        put_u64(scratch, chunk_start);
        put_u64(scratch, chunk_end);
        put_u64(scratch, chunk.size());
        put_u32(scratch, chunk_crc);
        put_string(scratch, cname);
        put_u64(scratch, csize);
        emit(scratch);
        emit(cdata, csize);
        entry.chunk_length = offset - entry.chunk_offset;

        // One message index per channel with messages in this chunk, in channel order.
        const uint64_t index_start = offset;
        for (std::size_t c = 0; c < chunk_index.size(); ++c) {
            auto& list = chunk_index[c];
            if (list.empty()) continue;
            // Log times of a log are normally in order; readers search them, so make sure.
            std::stable_sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
            entry.message_index_offsets.emplace_back(static_cast<uint16_t>(c + 1), offset);
            scratch.clear();
            put_u8(scratch, op_message_index);
            put_u64(scratch, 2 + 4 + 16 * list.size());
            put_u16(scratch, static_cast<uint16_t>(c + 1));
            put_u32(scratch, checked_u32(16 * list.size(), "message index"));
            for (const auto& [t, off] : list) {
                put_u64(scratch, t);
                put_u64(scratch, off);
            }
            emit(scratch);
            list.clear();
        }
        entry.message_index_length = offset - index_start;
        chunk_indexes.push_back(std::move(entry));
        ++counters.chunks;
        counters.uncompressed_bytes += chunk.size();
        counters.compressed_bytes += csize;
        chunk.clear();
    }
};

McapWriter::McapWriter(ByteSink& sink, McapOptions options) : impl_(std::make_unique<Impl>(sink, std::move(options)))
{
    std::vector<uint8_t> b(kMagic, kMagic + 8);
    std::vector<uint8_t> header;
    put_string(header, impl_->options.profile);
    put_string(header, impl_->options.library);
    put_record(b, op_header, header);
    impl_->emit(b);
}

McapWriter::~McapWriter() = default;

uint16_t McapWriter::add_schema(std::string_view name, std::string_view encoding, std::string_view data)
{
    auto& im = *impl_;
    if (im.schema_records.size() >= 65535) throw std::length_error("mcap: more than 65535 schemas");
    const auto id = static_cast<uint16_t>(im.schema_records.size() + 1);
    std::vector<uint8_t> content;
    put_u16(content, id);
    put_string(content, name);
    put_string(content, encoding);
    put_u32(content, checked_u32(data.size(), "schema"));
    put_bytes(content, data.data(), data.size());
    im.schema_records.push_back(im.definition(op_schema, content));
    return id;
}

uint16_t McapWriter::add_channel(uint16_t schema_id, std::string_view topic, std::string_view message_encoding,
                                 const std::map<std::string, std::string>& metadata)
{
    auto& im = *impl_;
    if (schema_id > im.schema_records.size()) throw std::invalid_argument("mcap: channel with an unknown schema id");
    if (im.channel_records.size() >= 65535) throw std::length_error("mcap: more than 65535 channels");
    const auto id = static_cast<uint16_t>(im.channel_records.size() + 1);
    std::vector<uint8_t> content;
    put_u16(content, id);
    put_u16(content, schema_id);
    put_string(content, topic);
    put_string(content, message_encoding);
    std::vector<uint8_t> map;
    for (const auto& [k, v] : metadata) {
        put_string(map, k);
        put_string(map, v);
    }
    put_u32(content, checked_u32(map.size(), "metadata"));
    put_bytes(content, map.data(), map.size());
    im.channel_records.push_back(im.definition(op_channel, content));
    im.channel_counts.push_back(0);
    im.chunk_index.emplace_back();
    return id;
}

void McapWriter::write_message(uint16_t channel_id, uint32_t sequence, uint64_t log_time, uint64_t publish_time,
                               const uint8_t* data, std::size_t size)
{
    auto& im = *impl_;
    if (im.finished) throw std::logic_error("mcap: message after finish()");
    if (channel_id == 0 || channel_id > im.channel_records.size())
        throw std::invalid_argument("mcap: message on an unknown channel id");
    if (im.chunk.empty()) {
        im.chunk_start = log_time;
        im.chunk_end = log_time;
    }
    im.chunk_index[channel_id - 1u].emplace_back(log_time, im.chunk.size());
    auto& c = im.chunk;
    put_u8(c, op_message);
    put_u64(c, 2 + 4 + 8 + 8 + size);
    put_u16(c, channel_id);
    put_u32(c, sequence);
    put_u64(c, log_time);
    put_u64(c, publish_time);
    put_bytes(c, data, size);
    im.chunk_start = std::min(im.chunk_start, log_time);
    im.chunk_end = std::max(im.chunk_end, log_time);
    if (im.message_count == 0 || log_time < im.start_time) im.start_time = log_time;
    if (im.message_count == 0 || log_time > im.end_time) im.end_time = log_time;
    ++im.message_count;
    ++im.channel_counts[channel_id - 1u];
    ++counters_.messages;
    if (c.size() >= im.options.chunk_size) im.close_chunk(counters_);
}

void McapWriter::finish()
{
    auto& im = *impl_;
    if (im.finished) return;
    im.close_chunk(counters_);
    im.finished = true;

    std::vector<uint8_t> b;
    std::vector<uint8_t> data_end;
    put_u32(data_end, im.data_crc);  // covers everything before this record
    put_record(b, op_data_end, data_end);
    im.emit(b, false);

    // The summary: one group per record kind, each found through a summary offset.
    const uint64_t summary_start = im.offset;
    uint32_t summary_crc = 0;
    std::vector<std::tuple<uint8_t, uint64_t, uint64_t>> groups;  // opcode, start, length
    auto write_group = [&](uint8_t opcode, const std::vector<uint8_t>& bytes) {
        if (bytes.empty()) return;
        groups.emplace_back(opcode, im.offset, bytes.size());
        summary_crc = crc32(bytes.data(), bytes.size(), summary_crc);
        im.emit(bytes, false);
    };
    b.clear();
    for (const auto& r : im.schema_records) put_bytes(b, r.data(), r.size());
    write_group(op_schema, b);
    b.clear();
    for (const auto& r : im.channel_records) put_bytes(b, r.data(), r.size());
    write_group(op_channel, b);

    std::vector<uint8_t> stats;
    put_u64(stats, im.message_count);
    put_u16(stats, static_cast<uint16_t>(im.schema_records.size()));
    put_u32(stats, static_cast<uint32_t>(im.channel_records.size()));
    put_u32(stats, 0);  // attachments
    put_u32(stats, 0);  // metadata
    put_u32(stats, checked_u32(im.chunk_indexes.size(), "chunk count"));
    put_u64(stats, im.start_time);
    put_u64(stats, im.end_time);
    std::vector<uint8_t> counts;
    for (std::size_t c = 0; c < im.channel_counts.size(); ++c) {
        put_u16(counts, static_cast<uint16_t>(c + 1));
        put_u64(counts, im.channel_counts[c]);
    }
    put_u32(stats, checked_u32(counts.size(), "channel counts"));
    put_bytes(stats, counts.data(), counts.size());
    b.clear();
    put_record(b, op_statistics, stats);
    write_group(op_statistics, b);

    b.clear();
    for (const auto& e : im.chunk_indexes) {
        const std::string_view cname = compression_name(im.options.compression);
        std::vector<uint8_t> content;
        put_u64(content, e.start_time);
        put_u64(content, e.end_time);
        put_u64(content, e.chunk_offset);
        put_u64(content, e.chunk_length);
        put_u32(content, checked_u32(10 * e.message_index_offsets.size(), "message index offsets"));
        for (const auto& [ch, off] : e.message_index_offsets) {
            put_u16(content, ch);
            put_u64(content, off);
        }
        put_u64(content, e.message_index_length);
        put_string(content, cname);
        put_u64(content, e.compressed_size);
        put_u64(content, e.uncompressed_size);
        put_record(b, op_chunk_index, content);
    }
    write_group(op_chunk_index, b);

    const uint64_t summary_offset_start = im.offset;
    b.clear();
    for (const auto& [opcode, start, length] : groups) {
        std::vector<uint8_t> content;
        put_u8(content, opcode);
        put_u64(content, start);
        put_u64(content, length);
        put_record(b, op_summary_offset, content);
    }
    summary_crc = crc32(b.data(), b.size(), summary_crc);
    im.emit(b, false);

    // The footer; its CRC covers the summary up to and including summary_offset_start.
    b.clear();
    put_u8(b, op_footer);
    put_u64(b, 8 + 8 + 4);
    put_u64(b, groups.empty() ? 0 : summary_start);
    put_u64(b, groups.empty() ? 0 : summary_offset_start);
    summary_crc = crc32(b.data(), b.size(), summary_crc);
    put_u32(b, summary_crc);
    put_bytes(b, kMagic, 8);
    im.emit(b, false);
}

}  // namespace ugv::foxglove
