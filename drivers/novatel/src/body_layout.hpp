// A body layout: everything the driver knows about one kind of log body, for both
// framings, so that a log table row can name it and the framing code stays generic.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "ugv/novatel/log_table.hpp"
#include "ugv/novatel/messages.hpp"

namespace ugv::novatel {

struct BodyLayout
{
    std::size_t binary_size;  // the body bytes read (a longer body is fine: newer receivers)
    // The body has at least binary_size bytes.
    Message (*from_binary)(const LogHeader& header, const uint8_t* body);
    // The fields after the ';'. False when they are too few or do not parse.
    bool (*from_ascii)(const LogHeader& header, std::string_view fields, Message& out);
    // A valid checksum does not make the content sane: false for values the pose filter
    // must not see (a position off the globe, an infinity).
    bool (*plausible)(const Message& m);
    // Empty when m is not this layout's struct.
    std::vector<uint8_t> (*to_binary)(const Message& m);
    std::string (*to_ascii)(const Message& m);
};

}  // namespace ugv::novatel
