#include "ugv/mcap/log_converter.hpp"

#include "ugv/reflect.hpp"

namespace ugv::mcap {

LogConverter::Channel& LogConverter::channel(std::string_view name)
{
    auto it = by_name_.find(std::string(name));
    if (it != by_name_.end()) return it->second;
    Channel c;
    c.wanted = std::regex_match(name.begin(), name.end(), channels_);
    return by_name_.emplace(std::string(name), std::move(c)).first->second;
}

uint16_t LogConverter::schema_id(const foxglove::TopicSpec& spec)
{
    auto it = schemas_.find(spec.schema_name);
    if (it != schemas_.end()) return it->second;
    const uint16_t id = writer_.add_schema(spec.schema_name, "jsonschema", foxglove::schema_of(spec));
    schemas_.emplace(spec.schema_name, id);
    return id;
}

void LogConverter::add(const LogEvent& event)
{
    ++counters_.events;
    Channel& ch = channel(event.channel);
    if (!ch.wanted) {
        ++counters_.filtered;
        return;
    }
    const std::string_view type = reflect::type_name_of(event.data, event.size);
    if (type.empty()) {
        ++counters_.unknown_type;
        return;
    }
    if (ch.type.empty()) {
        // The channel's topics, made when its first ugv message comes.
        ch.type = type;
        const bool raw = !std::regex_match(event.channel.begin(), event.channel.end(), no_raw_);
        for (auto& spec : foxglove::topics_for(event.channel, type, raw)) {
            Topic t;
            t.channel_id = writer_.add_channel(schema_id(spec), spec.topic, "json");
            t.spec = std::move(spec);
            ch.topics.push_back(std::move(t));
        }
    } else if (ch.type != type) {
        ++counters_.malformed;
        return;
    }
    if (!reflect::well_formed(event.data, event.size)) {
        ++counters_.malformed;
        return;
    }
    const auto log_time = static_cast<uint64_t>(event.utime < 0 ? 0 : event.utime) * 1000;
    bool same_message = false;  // the maps decode once for their raw and grid topics
    for (Topic& t : ch.topics) {
        // False also for a status without a change: no Log for it.
        const bool made = converter_.convert(t.spec, event.data, event.size, json_, same_message);
        same_message = true;
        if (!made) continue;
        writer_.write_message(t.channel_id, t.sequence++, log_time, log_time,
                              reinterpret_cast<const uint8_t*>(json_.data()), json_.size());
        ++counters_.messages;
    }
    ++counters_.converted;
    ++ch.converted;
}

std::map<std::string, uint64_t> LogConverter::channel_counts() const
{
    std::map<std::string, uint64_t> out;
    for (const auto& [name, ch] : by_name_)
        if (ch.converted > 0) out[name] = ch.converted;
    return out;
}

}  // namespace ugv::mcap
