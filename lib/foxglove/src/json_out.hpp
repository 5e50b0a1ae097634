// A small JSON text builder for the Foxglove messages: commas placed by the caller's
// structure, numbers as the shortest text that reads back the same, bytes as base64.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace ugv::foxglove::detail {

class JsonOut
{
public:
    explicit JsonOut(std::string& out) : out_(out) { out_.clear(); }

    JsonOut& begin_object() { sep(); out_ += '{'; first_.push_back(true); return *this; }
    JsonOut& end_object() { out_ += '}'; first_.pop_back(); return *this; }
    JsonOut& begin_array() { sep(); out_ += '['; first_.push_back(true); return *this; }
    JsonOut& end_array() { out_ += ']'; first_.pop_back(); return *this; }
    JsonOut& key(std::string_view k)
    {
        sep();
        out_ += '"';
        out_ += k;
        out_ += "\":";
        after_key_ = true;
        return *this;
    }
    JsonOut& string(std::string_view s);
    JsonOut& boolean(bool b) { sep(); out_ += b ? "true" : "false"; return *this; }
    // Non-finite numbers have no JSON text: they become `fallback`.
    JsonOut& number(double v, double fallback = 0) { return num(std::isfinite(v) ? v : fallback); }
    JsonOut& integer(int64_t v)
    {
        sep();
        char b[24];
        out_.append(b, std::to_chars(b, b + sizeof b, v).ptr);
        return *this;
    }
    JsonOut& base64(const uint8_t* data, std::size_t size);
    // {"sec":..,"nsec":..} of a time in microseconds since the epoch.
    JsonOut& time_us(int64_t utime);
    JsonOut& vec3(std::string_view k, double x, double y, double z)
    {
        key(k).begin_object().key("x").number(x).key("y").number(y).key("z").number(z).end_object();
        return *this;
    }
    JsonOut& quat(std::string_view k, double w, double x, double y, double z)
    {
        key(k).begin_object().key("x").number(x).key("y").number(y).key("z").number(z).key("w").number(w, 1).end_object();
        return *this;
    }

private:
    void sep()
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
    JsonOut& num(double v)
    {
        sep();
        char b[32];
        out_.append(b, std::to_chars(b, b + sizeof b, v).ptr);
        return *this;
    }

    std::string& out_;
    std::vector<bool> first_;
    bool after_key_ = false;
};

}  // namespace ugv::foxglove::detail
