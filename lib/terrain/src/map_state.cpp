#include "ugv/terrain/map_state.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace ugv::terrain {

namespace {

static_assert(std::endian::native == std::endian::little, "the map file is written in the host's order");

constexpr char kMagic[8] = {'U', 'G', 'V', 'T', 'M', 'A', 'P', '\0'};
// 2: each cell's newest time, and the epoch it counts from. A file of version 1 (no times)
// is refused like any other version: its cells' ages are unknowable.
constexpr uint32_t kVersion = 2;
constexpr std::size_t kHeaderBytes = 8 + 4 + 4 * 4 + 6 * 8 + 2 * 8 + 4;  // magic .. cell count
constexpr std::size_t kCellBytes = 4 + sizeof(CellSums) + 4 + 2 * 4 + 4;
constexpr std::size_t kChecksumBytes = 8;

uint64_t fnv1a(const uint8_t* p, std::size_t n)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (std::size_t i = 0; i < n; ++i) {
        h ^= p[i];
        h *= 0x100000001b3ull;
    }
    return h;
}

class Writer
{
public:
    template <typename T>
    void put(const T& v)
    {
        const auto* p = reinterpret_cast<const uint8_t*>(&v);
        out.insert(out.end(), p, p + sizeof(T));
    }
    std::vector<uint8_t> out;
};

class Reader
{
public:
    explicit Reader(const uint8_t* p) : p_(p) {}
    template <typename T>
    T get()
    {
        T v{};
        std::memcpy(&v, p_ + at_, sizeof(T));  // sizes are checked before reading
        at_ += sizeof(T);
        return v;
    }

private:
    const uint8_t* p_;
    std::size_t at_ = 0;
};

bool finite(const CellSums& c)
{
    return std::isfinite(c.w) && c.w > 0.0f && std::isfinite(c.x_wx) && std::isfinite(c.y_wy) &&
           std::isfinite(c.z_wz) && std::isfinite(c.z_ref_m) && std::isfinite(c.x_wx2) && std::isfinite(c.y_wy2) &&
           std::isfinite(c.z_wz2);
}

}  // namespace

std::size_t max_encoded_size(int nx, int ny)
{
    return kHeaderBytes + static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * kCellBytes + kChecksumBytes;
}

std::vector<uint8_t> encode_map_state(const MapState& s)
{
    Writer w;
    w.out.reserve(kHeaderBytes + s.cells.size() * kCellBytes + kChecksumBytes);
    for (char c : kMagic) w.put(c);
    w.put(kVersion);
    w.put(int32_t{s.nx});
    w.put(int32_t{s.ny});
    w.put(static_cast<int32_t>(s.statistics));
    w.put(int32_t{0});
    w.put(s.grid_size_m);
    w.put(s.reference_x_m);
    w.put(s.reference_y_m);
    w.put(s.anchor_x_m);
    w.put(s.anchor_y_m);
    w.put(s.anchor_yaw_rad);
    w.put(s.utime_us);
    w.put(s.epoch_us);
    w.put(static_cast<uint32_t>(s.cells.size()));
    for (const SavedCell& c : s.cells) {
        w.put(c.index);
        w.put(c.sums);
        w.put(c.tally.count);
        w.put(c.tally.extremes.z_max_m);
        w.put(c.tally.extremes.z_min_m);
        w.put(c.tally.newest_ms);
    }
    w.put(fnv1a(w.out.data(), w.out.size()));
    return std::move(w.out);
}

std::optional<MapState> decode_map_state(const uint8_t* data, std::size_t size, std::string& why)
{
    if (size < kHeaderBytes + kChecksumBytes || std::memcmp(data, kMagic, sizeof kMagic) != 0) {
        why = "not a ugv-terrain map file";
        return std::nullopt;
    }
    Reader r(data + sizeof kMagic);
    if (const auto v = r.get<uint32_t>(); v != kVersion) {
        why = "format version " + std::to_string(v) + ", expected " + std::to_string(kVersion);
        return std::nullopt;
    }
    MapState s;
    s.nx = r.get<int32_t>();
    s.ny = r.get<int32_t>();
    const auto stats = r.get<int32_t>();
    (void)r.get<int32_t>();
    s.grid_size_m = r.get<double>();
    s.reference_x_m = r.get<double>();
    s.reference_y_m = r.get<double>();
    s.anchor_x_m = r.get<double>();
    s.anchor_y_m = r.get<double>();
    s.anchor_yaw_rad = r.get<double>();
    s.utime_us = r.get<int64_t>();
    s.epoch_us = r.get<int64_t>();
    const auto count = r.get<uint32_t>();
    if (s.nx <= 0 || s.ny <= 0 || s.nx > 100'000 || s.ny > 100'000 || (stats != 0 && stats != 1)) {
        why = "bad layout";
        return std::nullopt;
    }
    s.statistics = static_cast<StatisticsKind>(stats);
    const uint64_t cells = static_cast<uint64_t>(s.nx) * static_cast<uint64_t>(s.ny);
    if (count > cells || size != kHeaderBytes + count * kCellBytes + kChecksumBytes) {
        why = "truncated or wrong length (" + std::to_string(size) + " bytes for " + std::to_string(count) + " cells)";
        return std::nullopt;
    }
    uint64_t sum = 0;
    std::memcpy(&sum, data + size - kChecksumBytes, kChecksumBytes);
    if (sum != fnv1a(data, size - kChecksumBytes)) {
        why = "checksum mismatch";
        return std::nullopt;
    }
    if (!(std::isfinite(s.grid_size_m) && std::isfinite(s.reference_x_m) && std::isfinite(s.reference_y_m) &&
          std::isfinite(s.anchor_x_m) && std::isfinite(s.anchor_y_m) && std::isfinite(s.anchor_yaw_rad))) {
        why = "non-finite position";
        return std::nullopt;
    }
    s.cells.resize(count);
    for (uint32_t k = 0; k < count; ++k) {
        SavedCell& c = s.cells[k];
        c.index = r.get<uint32_t>();
        c.sums = r.get<CellSums>();
        c.tally.count = r.get<uint32_t>();
        c.tally.extremes.z_max_m = r.get<float>();
        c.tally.extremes.z_min_m = r.get<float>();
        c.tally.newest_ms = r.get<TimeTick>();
        const bool in_order = k == 0 || c.index > s.cells[k - 1].index;
        if (c.index >= cells || !in_order || !finite(c.sums) || c.tally.count == 0 ||
            !std::isfinite(c.tally.extremes.z_max_m) || !std::isfinite(c.tally.extremes.z_min_m) ||
            c.tally.newest_ms == kNoTime) {
            why = "bad cell " + std::to_string(k);
            return std::nullopt;
        }
    }
    return s;
}

}  // namespace ugv::terrain
