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

// One field of a type, in wire order: what a generic consumer (a JSON Schema, the Foxglove
// conversions) needs to know without the generated class.
struct FieldInfo
{
    std::string_view name;
    std::string_view type;          // an LCM primitive ("float", "int32_t", "string", ...) or "ugv.pose_t"
    int fixed_length;               // > 0: an array of this many elements
    std::string_view length_field;  // not empty: an array sized by this (earlier) field
};

// The fields of the named type (e.g. "ugv.pose_t"); nullptr when no ugv type has that name.
const std::vector<FieldInfo>* fields_of(std::string_view type_name);

// The name of the ugv type whose fingerprint the bytes start with; empty when none.
std::string_view type_name_of(const void* data, std::size_t size);

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
