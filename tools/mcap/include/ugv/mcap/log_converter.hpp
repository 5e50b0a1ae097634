// An lcm-logger log into MCAP: each event of a matching channel onto its Foxglove topics
// (lib/foxglove), log time = the logger's receive time. No I/O: events in, records out.
#pragma once

#include <cstdint>
#include <map>
#include <regex>
#include <string>
#include <unordered_map>
#include <vector>

#include "ugv/foxglove/mcap_writer.hpp"
#include "ugv/foxglove/topics.hpp"
#include "ugv/mcap/lcm_log_scanner.hpp"

namespace ugv::mcap {

struct ConvertCounters
{
    uint64_t events = 0;          // events read from the log
    uint64_t filtered = 0;        // on channels --channels leaves out
    uint64_t converted = 0;       // events that decoded (each on all its topics)
    uint64_t unknown_type = 0;    // not a ugv type (no topic)
    uint64_t malformed = 0;       // a ugv fingerprint whose bytes do not decode, or another type than the channel's
    uint64_t messages = 0;        // MCAP messages written, all topics
};

class LogConverter
{
public:
    // channels: the channels converted; no_raw: those among them whose own JSON topic is left
    // out (their Foxglove topics stay), e.g. the maps, whose cells the grids carry.
    LogConverter(foxglove::McapWriter& writer, std::regex channels, std::regex no_raw = std::regex("$^"))
        : writer_(writer), channels_(std::move(channels)), no_raw_(std::move(no_raw))
    {
    }

    void add(const LogEvent& event);

    const ConvertCounters& counters() const { return counters_; }
    // Events converted per channel (the raw topic's message count).
    std::map<std::string, uint64_t> channel_counts() const;

private:
    struct Topic
    {
        foxglove::TopicSpec spec;
        uint16_t channel_id = 0;
        uint32_t sequence = 0;
    };
    struct Channel
    {
        bool wanted = false;
        std::string type;  // set by the first ugv message
        std::vector<Topic> topics;
        uint64_t converted = 0;
    };

    Channel& channel(std::string_view name);
    uint16_t schema_id(const foxglove::TopicSpec& spec);

    foxglove::McapWriter& writer_;
    std::regex channels_, no_raw_;
    std::unordered_map<std::string, Channel> by_name_;
    std::map<std::string, uint16_t> schemas_;  // by schema name
    foxglove::Converter converter_;
    std::string json_;
    ConvertCounters counters_;
};

}  // namespace ugv::mcap
