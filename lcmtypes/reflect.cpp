#include "ugv/reflect.hpp"
#include "ugv/reflect_message.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <memory>

#include "ugv/candidate_arcs_t.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/gps_fix_t.hpp"
#include "ugv/gps_velocity_t.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/point_cloud_t.hpp"
#include "ugv/pose_t.hpp"
#include "ugv/raw_bytes_t.hpp"
#include "ugv/servo_command_t.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv/sim_truth_t.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv/traversability_map_t.hpp"

namespace ugv::reflect {
namespace {

// A minimal streaming JSON writer into the caller's string (its capacity is reused from
// message to message): commas are placed by tracking whether the current container already
// has an element.
class JsonWriter
{
public:
    explicit JsonWriter(std::string& out) : out_(out) {}
    void begin_object() { element(); out_ += '{'; first_.push_back(true); }
    void end_object() { out_ += '}'; first_.pop_back(); }
    void begin_array() { element(); out_ += '['; first_.push_back(true); }
    void end_array() { out_ += ']'; first_.pop_back(); }
    void key(const char* k)
    {
        element();
        out_ += '"';
        out_ += k;
        out_ += "\":";
        after_key_ = true;
    }
    void value(const std::string& s) { element(); out_ += json_quote(s); }
    void value(bool b) { element(); out_ += b ? "true" : "false"; }
    void value(double d) { number(d); }
    void value(float f) { number(f); }
    void value(int8_t v) { integer(v); }
    void value(uint8_t v) { integer(v); }
    void value(int16_t v) { integer(v); }
    void value(int32_t v) { integer(v); }
    void value(int64_t v) { integer(v); }
    // A numeric array at once, through a stack buffer: the maps' arrays of 22500 cells are
    // most of ugv-mcap's text, and per-element appends to the string cost as much as the digits.
    template <typename T>
    void array(const T* p, std::size_t n)
    {
        begin_array();
        char buf[4096];
        std::size_t at = 0;
        for (std::size_t k = 0; k < n; ++k) {
            if (at > sizeof buf - 48) {
                out_.append(buf, at);
                at = 0;
            }
            if (k > 0) buf[at++] = ',';
            at = static_cast<std::size_t>(put(buf + at, p[k]) - buf);
        }
        out_.append(buf, at);
        end_array();
    }

private:
    void element()
    {
        if (after_key_) {
            after_key_ = false;
            return;
        }
        if (!first_.empty()) {
            if (!first_.back()) out_ += ',';
            first_.back() = false;
        }
    }
    void integer(long long v)
    {
        element();
        char buf[24];
        out_.append(buf, put(buf, v));
    }
    template <typename Float>
    void number(Float d)
    {
        element();
        char buf[40];
        out_.append(buf, put(buf, d));
    }
    // One number's text at o (room for 40 chars); returns its end. Integers of any width.
    template <typename Int>
    static char* put(char* o, Int v)
    {
        return std::to_chars(o, o + 24, static_cast<long long>(v)).ptr;
    }
    // The shortest text that reads back as the same value (to_chars is also several times
    // faster than printf, which matters for ugv-mcap on a whole map per message).
    static char* put(char* o, double d)
    {
        if (!std::isfinite(d)) return std::copy_n("null", 4, o);
        return std::to_chars(o, o + 40, d).ptr;
    }
    // Floats through a cache of their texts: a map's cells repeat many values (ages,
    // certainties, flat ground), ~60 % of a demo map's finite cells hit it (ugv-mcap).
    static char* put(char* o, float f)
    {
        if (!std::isfinite(f)) return std::copy_n("null", 4, o);
        const auto bits = std::bit_cast<uint32_t>(f);
        FloatText& slot = float_texts()[(bits * 0x9E3779B1u) >> (32 - kFloatTextBits)];
        if (slot.bits != bits) {
            slot.bits = bits;
            slot.size = static_cast<uint8_t>(std::to_chars(slot.text, slot.text + sizeof slot.text, f).ptr - slot.text);
        }
        std::memcpy(o, slot.text, sizeof slot.text);  // the whole slot: o has room for 40
        return o + slot.size;
    }
    // The last float seen in each slot (by a hash of its bits) and its to_chars text.
    struct FloatText
    {
        uint32_t bits = 0xffffffffu;  // a NaN: never looked up
        uint8_t size = 0;
        char text[16] = {};  // the longest is 15: "-1.17549435e-38"
    };
    static constexpr int kFloatTextBits = 12;
    using FloatTexts = std::array<FloatText, 1u << kFloatTextBits>;
    // Per thread, from the heap when a thread first prints a float: 96 kB of static TLS would
    // be set up in every thread of every program that links the reflection.
    static FloatTexts& float_texts()
    {
        thread_local std::unique_ptr<FloatTexts> texts;
        if (!texts) texts = std::make_unique<FloatTexts>();
        return *texts;
    }

    std::string& out_;
    std::vector<bool> first_;
    bool after_key_ = false;
};

using PrintFn = bool (*)(const void*, std::size_t, std::string&);
using FitsFn = bool (*)(const uint8_t*, std::size_t, std::size_t&);

struct TypeEntry
{
    const char* name;
    int64_t hash;
    PrintFn print;
    FitsFn fits;  // the body (after the hash) is well formed
    const std::vector<FieldInfo>* fields;
};

// Helpers of the generated fits_* functions: bounds-checked walking of LCM's encoding.
bool skip(std::size_t n, std::size_t& p, std::size_t bytes)
{
    if (bytes > n - p) return false;
    p += bytes;
    return true;
}

bool skip(std::size_t n, std::size_t& p, std::size_t count, std::size_t elem)
{
    if (count > (n - p) / elem) return false;
    p += count * elem;
    return true;
}

bool read_int(const uint8_t* b, std::size_t n, std::size_t& p, std::size_t bytes, int64_t& v)
{
    if (bytes > n - p) return false;
    uint64_t u = 0;
    for (std::size_t k = 0; k < bytes; ++k) u = (u << 8) | b[p + k];
    const unsigned shift = static_cast<unsigned>(64 - 8 * bytes);  // sign-extend
    v = static_cast<int64_t>(u << shift) >> shift;
    p += bytes;
    return true;
}

bool skip_string(const uint8_t* b, std::size_t n, std::size_t& p)
{
    int64_t len = 0;
    // The length counts the terminating NUL: 0 is malformed (lcm-gen would throw).
    return read_int(b, n, p, 4, len) && len >= 1 && skip(n, p, static_cast<std::size_t>(len));
}

template <typename T, void (*Json)(JsonWriter&, const T&)>
bool decode_and_print(const void* data, std::size_t size, std::string& json)
{
    T msg{};  // value-initialised: decode fills every field, but the compiler cannot see that
    if (size > static_cast<std::size_t>(INT32_MAX)) return false;
    // Only called after well_formed(): decode cannot throw or over-allocate here.
    const int n = msg.decode(data, 0, static_cast<int>(size));
    if (n < 0 || static_cast<std::size_t>(n) != size) return false;
    json.clear();
    json.reserve(3 * size + 256);  // a float array prints in about 2-3 times its bytes: grow once
    JsonWriter w(json);
    Json(w, msg);
    return true;
}

#include "ugv/reflect_generated.inc"

}  // namespace

template <typename Msg>
void message_json(const Msg& msg, std::string& json)
{
    json.clear();
    JsonWriter w(json);
    json_message(w, msg);
}
#define UGV_REFLECT_INSTANTIATE(T) template void message_json<T>(const T&, std::string&);
UGV_REFLECT_FOR_EACH_TYPE(UGV_REFLECT_INSTANTIATE)
#undef UGV_REFLECT_INSTANTIATE

std::vector<TypeInfo> all_types()
{
    std::vector<TypeInfo> out;
    for (const auto& e : type_table()) out.push_back({e.name, e.hash});
    return out;
}

namespace {
const TypeEntry* find_entry(const void* data, std::size_t size)
{
    if (size < 8) return nullptr;
    const auto* b = static_cast<const uint8_t*>(data);
    uint64_t h = 0;
    for (int k = 0; k < 8; ++k) h = (h << 8) | b[k];
    for (const auto& e : type_table())
        if (static_cast<uint64_t>(e.hash) == h) return &e;
    return nullptr;
}

bool body_fits(const TypeEntry& e, const void* data, std::size_t size)
{
    std::size_t p = 8;
    return e.fits(static_cast<const uint8_t*>(data), size, p) && p == size;
}
}  // namespace

const std::vector<FieldInfo>* fields_of(std::string_view type_name)
{
    for (const auto& e : type_table())
        if (type_name == e.name) return e.fields;
    return nullptr;
}

std::string_view type_name_of(const void* data, std::size_t size)
{
    const TypeEntry* e = find_entry(data, size);
    return e ? std::string_view(e->name) : std::string_view();
}

bool well_formed(const void* data, std::size_t size)
{
    const TypeEntry* e = find_entry(data, size);
    return e && body_fits(*e, data, size);
}

DecodeResult to_json(const void* data, std::size_t size, std::string& type_name, std::string& json)
{
    if (size < 8) return DecodeResult::malformed;
    const TypeEntry* e = find_entry(data, size);
    if (!e) return DecodeResult::unknown_type;
    type_name = e->name;
    if (!body_fits(*e, data, size)) return DecodeResult::malformed;
    return e->print(data, size, json) ? DecodeResult::ok : DecodeResult::malformed;
}

std::string json_quote(std::string_view s)
{
    std::string out = "\"";
    for (const char c : s) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
                out += buf;
            } else {
                out += c;
            }
        }
    }
    out += '"';
    return out;
}

}  // namespace ugv::reflect
