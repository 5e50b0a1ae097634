#include "ugv/reflect.hpp"

#include <cmath>
#include <cstdio>
#include <iterator>

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

namespace ugv::reflect {
namespace {

// A minimal streaming JSON writer: commas are placed by tracking whether the current
// container already has an element.
class JsonWriter
{
public:
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
    void value(double d) { number(d, "%.17g"); }
    void value(float f) { number(f, "%.9g"); }
    void value(int8_t v) { integer(v); }
    void value(uint8_t v) { integer(v); }
    void value(int16_t v) { integer(v); }
    void value(int32_t v) { integer(v); }
    void value(int64_t v) { integer(v); }
    std::string take() { return std::move(out_); }

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
        out_ += std::to_string(v);
    }
    void number(double d, const char* fmt)
    {
        element();
        if (!std::isfinite(d)) {
            out_ += "null";
            return;
        }
        char buf[40];
        std::snprintf(buf, sizeof buf, fmt, d);
        out_ += buf;
    }

    std::string out_;
    std::vector<bool> first_;
    bool after_key_ = false;
};

using PrintFn = bool (*)(const void*, std::size_t, std::string&);

struct TypeEntry
{
    const char* name;
    int64_t hash;
    PrintFn print;
};

template <typename T, void (*Json)(JsonWriter&, const T&)>
bool decode_and_print(const void* data, std::size_t size, std::string& json)
{
    T msg{};  // value-initialised: decode fills every field, but the compiler cannot see that
    if (size > static_cast<std::size_t>(INT32_MAX)) return false;
    const int n = msg.decode(data, 0, static_cast<int>(size));
    if (n < 0 || static_cast<std::size_t>(n) != size) return false;
    JsonWriter w;
    Json(w, msg);
    json = w.take();
    return true;
}

#include "ugv/reflect_generated.inc"

}  // namespace

std::vector<TypeInfo> all_types()
{
    std::vector<TypeInfo> out;
    for (const auto& e : type_table()) out.push_back({e.name, e.hash});
    return out;
}

DecodeResult to_json(const void* data, std::size_t size, std::string& type_name, std::string& json)
{
    if (size < 8) return DecodeResult::malformed;
    const auto* b = static_cast<const uint8_t*>(data);
    uint64_t h = 0;
    for (int k = 0; k < 8; ++k) h = (h << 8) | b[k];
    for (const auto& e : type_table()) {
        if (static_cast<uint64_t>(e.hash) != h) continue;
        type_name = e.name;
        return e.print(data, size, json) ? DecodeResult::ok : DecodeResult::malformed;
    }
    return DecodeResult::unknown_type;
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
