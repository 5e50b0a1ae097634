// Decoding of any ugv message by its fingerprint, and printing it as JSON.
//
// LCM messages carry no type name on the wire, only an 8-byte fingerprint; like lcm-spy, we
// find the type by that fingerprint among the ugv types. Used by ugv-dump, ugv-expect and
// the fuzz targets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace ugv::reflect {

struct TypeInfo
{
    std::string name;  // e.g. "ugv.pose_t"
    int64_t hash;      // the LCM fingerprint
};

// Every ugv type, in the order of the .lcm files.
std::vector<TypeInfo> all_types();

enum class DecodeResult { ok, unknown_type, malformed };

// Decodes `size` bytes as the ugv type whose fingerprint they start with. On success fills
// type_name and json (one JSON object with every field; NaN and Inf print as null).
DecodeResult to_json(const void* data, std::size_t size, std::string& type_name, std::string& json);

// True when the bytes are exactly one well-formed message of a ugv type: its fingerprint is
// known, every string length is at least 1, every array count is non-negative, and nothing
// reaches past the end. Check this before lcm-gen's decode(): in LCM 1.3.1 it throws
// std::length_error on a zero string length and allocates whatever a count says (found by
// fuzz_lcm_decode).
bool well_formed(const void* data, std::size_t size);

// A JSON string literal for s, quotes included.
std::string json_quote(std::string_view s);

}  // namespace ugv::reflect
