// A small JSON document model: enough to read the objects ugv::reflect prints.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ugv::expect {

struct JsonValue
{
    enum class Kind { null, boolean, number, string, array, object };
    Kind kind = Kind::null;
    bool boolean = false;
    double number = 0;
    std::string string;
    std::vector<JsonValue> array;
    std::map<std::string, JsonValue> object;
};

// Parses a whole document; nullopt when it is not valid JSON.
std::optional<JsonValue> parse_json(std::string_view text);

}  // namespace ugv::expect
