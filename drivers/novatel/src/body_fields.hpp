// Field access shared by the body layouts and the framings: little-endian binary values,
// ASCII fields that may be empty, and printf-style text for the encoders.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ugv/novatel/text_fields.hpp"

namespace ugv::novatel {

template <typename T>
T get(const uint8_t* p)
{
    T v;
    std::memcpy(&v, p, sizeof v);  // the host is little-endian like the receiver (x86, ARM)
    return v;
}

template <typename T>
void put(std::vector<uint8_t>& out, std::size_t offset, T v)
{
    std::memcpy(out.data() + offset, &v, sizeof v);
}

// Fills d from a field when it holds a number; an empty field leaves the NaN default.
inline bool number(FieldReader& r, double& d)
{
    std::string_view f;
    if (!r.next(f)) {
        return false;
    }
    parse_double(f, d);
    return true;
}

inline bool count(FieldReader& r, int& n)
{
    std::string_view f;
    if (!r.next(f)) {
        return false;
    }
    int64_t v = 0;
    if (parse_int(f, v)) {
        n = static_cast<int>(v);
    }
    return true;
}

inline std::string format(const char* fmt, auto... args)
{
    char buf[512];
    const int n = std::snprintf(buf, sizeof buf, fmt, args...);
    return std::string(buf, n > 0 ? static_cast<std::size_t>(n) : 0U);
}

// An enum as the receiver prints it: its name, or its number when the table lacks it.
inline std::string enum_name(std::optional<std::string_view> name, uint32_t value)
{
    return name ? std::string(*name) : std::to_string(value);
}

}  // namespace ugv::novatel
