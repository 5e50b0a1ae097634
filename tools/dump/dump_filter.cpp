#include "ugv/dump/dump_filter.hpp"

namespace ugv::dump {

namespace {
// The "utime" field is first in every ugv type: pull it out of the fields object.
std::string utime_of(const std::string& fields)
{
    const std::string key = "\"utime\":";
    const auto p = fields.find(key);
    if (p == std::string::npos) return "null";
    const auto start = p + key.size();
    auto end = fields.find_first_of(",}", start);
    return fields.substr(start, end - start);
}
}  // namespace

std::string json_line(const std::string& channel, const std::string& type_name, const std::string& fields_json,
                      int64_t recv_utime)
{
    std::string out = "{\"channel\":\"";
    for (const char c : channel) {
        if (c == '"' || c == '\\') out += '\\';
        out += c;
    }
    out += "\",\"utime\":" + utime_of(fields_json) + ",\"recv_utime\":" + std::to_string(recv_utime) + ",\"type\":\"" +
           type_name + "\",\"fields\":" + fields_json + "}";
    return out;
}

DumpFilter::DumpFilter(const std::string& channel_regex, int64_t count) : re_(channel_regex), count_(count) {}

}  // namespace ugv::dump
