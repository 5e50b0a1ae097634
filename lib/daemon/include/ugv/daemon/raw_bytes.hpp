// The raw_bytes_t a device daemon publishes of its wire traffic (publish_raw = true).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "ugv/raw_bytes_t.hpp"

namespace ugv::daemon {

raw_bytes_t raw_bytes_message(const std::string& device, bool to_device, const uint8_t* data, std::size_t n,
                              int64_t utime, int64_t seq);

}  // namespace ugv::daemon
