#include <catch2/catch.hpp>

#include <spdlog/sinks/ostream_sink.h>

#include <sstream>

#include "ugv/runtime/rate_limited_log.hpp"

TEST_CASE("repeated errors are logged once per interval, with the count of the ones held back")
{
    std::ostringstream out;
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(out);
    auto logger = std::make_shared<spdlog::logger>("t", sink);
    logger->set_pattern("%v");
    spdlog::set_default_logger(logger);

    ugv::runtime::RateLimitedLog log(1'000'000);
    CHECK(log.log(spdlog::level::warn, "crc", "crc error", 0));
    for (int k = 1; k <= 37; ++k) CHECK_FALSE(log.log(spdlog::level::warn, "crc", "crc error", k * 10'000));
    CHECK(log.log(spdlog::level::warn, "other", "timeout", 500'000));  // another key is not held back
    CHECK(log.log(spdlog::level::warn, "crc", "crc error", 1'500'000));
    CHECK(log.suppressed_total() == 37);
    CHECK(out.str() == "crc error\ntimeout\ncrc error (repeated 37 times in the last 1.5 s)\n");
}
