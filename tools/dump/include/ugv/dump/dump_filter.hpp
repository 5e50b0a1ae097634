// What ugv-dump prints and when it is done: a channel filter, a count, a timeout.
#pragma once

#include <cstdint>
#include <regex>
#include <string>

namespace ugv::dump {

// One output line: {"channel":..,"utime":..,"recv_utime":..,"type":..,"fields":{..}}.
// utime is the message's own field (null when the type has none), recv_utime the bus's.
std::string json_line(const std::string& channel, const std::string& type_name, const std::string& fields_json,
                      int64_t recv_utime);

class DumpFilter
{
public:
    DumpFilter(const std::string& channel_regex, int64_t count);
    bool wants(const std::string& channel) const { return std::regex_match(channel, re_); }
    void printed() { ++printed_; }
    bool done() const { return count_ > 0 && printed_ >= count_; }
    int64_t printed_count() const { return printed_; }

private:
    std::regex re_;
    int64_t count_;
    int64_t printed_ = 0;
};

}  // namespace ugv::dump
