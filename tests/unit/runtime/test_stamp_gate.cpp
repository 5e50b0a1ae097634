#include <catch2/catch.hpp>

#include <spdlog/sinks/ostream_sink.h>

#include <algorithm>
#include <limits>
#include <sstream>
#include <string>

#include "ugv/runtime/stamp_gate.hpp"

using ugv::runtime::check_stamp;
using ugv::runtime::StampGate;
using ugv::runtime::StampLimits;
using ugv::runtime::StampVerdict;

namespace {

constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
constexpr int64_t kMin = std::numeric_limits<int64_t>::min();
constexpr int64_t kNow = 1'764'600'000'000'000;  // 2025-12
constexpr int64_t kYear = 365LL * 86'400'000'000LL;

}  // namespace

TEST_CASE("check_stamp: within [now - age, now + ahead] is ok, with the bounds included")
{
    const StampLimits l{.max_ahead_us = 2'000'000, .max_age_us = 3'000'000};
    CHECK(check_stamp(kNow, kNow, l) == StampVerdict::ok);
    CHECK(check_stamp(kNow + 2'000'000, kNow, l) == StampVerdict::ok);
    CHECK(check_stamp(kNow + 2'000'001, kNow, l) == StampVerdict::ahead);
    CHECK(check_stamp(kNow - 3'000'000, kNow, l) == StampVerdict::ok);
    CHECK(check_stamp(kNow - 3'000'001, kNow, l) == StampVerdict::too_old);
    CHECK(check_stamp(kNow + kYear, kNow, l) == StampVerdict::ahead);
    CHECK(check_stamp(kNow - 3'600'000'000, kNow, l) == StampVerdict::too_old);
}

TEST_CASE("check_stamp: the extremes of int64 on either side never overflow")
{
    const StampLimits l{.max_ahead_us = 2'000'000, .max_age_us = 3'000'000};
    CHECK(check_stamp(kMax, kNow, l) == StampVerdict::ahead);
    CHECK(check_stamp(kMin, kNow, l) == StampVerdict::too_old);
    CHECK(check_stamp(0, kNow, l) == StampVerdict::too_old);
    CHECK(check_stamp(-1, kNow, l) == StampVerdict::too_old);
    CHECK(check_stamp(kMax, kMin, l) == StampVerdict::ahead);
    CHECK(check_stamp(kMin, kMax, l) == StampVerdict::too_old);
    CHECK(check_stamp(kMax, kMax, l) == StampVerdict::ok);
    CHECK(check_stamp(kMin, kMin, l) == StampVerdict::ok);
    const StampLimits wide{.max_ahead_us = kMax, .max_age_us = kMax};
    CHECK(check_stamp(kMax, 0, wide) == StampVerdict::ok);
    CHECK(check_stamp(0, kMax, wide) == StampVerdict::ok);
    CHECK(check_stamp(kMax, kMin, wide) == StampVerdict::ahead);  // 2^64 - 1 apart
    CHECK(check_stamp(kMin, kMax, wide) == StampVerdict::too_old);
}

TEST_CASE("StampGate counts each refusal by kind and logs once per interval per input")
{
    static std::ostringstream out;  // the default logger outlives this test case
    auto sink = std::make_shared<spdlog::sinks::ostream_sink_mt>(out);
    auto logger = std::make_shared<spdlog::logger>("t", sink);
    logger->set_pattern("%v");
    spdlog::set_default_logger(logger);

    StampGate gate({.max_ahead_us = 2'000'000, .max_age_us = 2'000'000});
    const int fix = gate.add_input("GPS_FIX");
    const int imu = gate.add_input("IMU");
    CHECK(gate.accept(fix, kNow, kNow));
    CHECK_FALSE(gate.accept(fix, kMax, kNow));
    CHECK_FALSE(gate.accept(fix, kNow + kYear, kNow + 10));
    CHECK_FALSE(gate.accept(imu, kMin, kNow + 20));
    CHECK_FALSE(gate.accept(imu, kNow - 3'600'000'000, kNow + 30));
    CHECK(gate.accept(imu, kNow + 40, kNow + 40));
    CHECK(gate.counters().stamps_ahead == 2);
    CHECK(gate.counters().stamps_too_old == 2);
    const std::string text = out.str();
    // One line per input and kind within the 5 s interval: GPS_FIX ahead, IMU old.
    CHECK(std::count(text.begin(), text.end(), '\n') == 2);
    CHECK(text.find("GPS_FIX: message stamped 9223372036854775807") != std::string::npos);
    CHECK(text.find("IMU: message stamped -9223372036854775808") != std::string::npos);
    CHECK(gate.rejecting().empty());  // a few refusals, not a second of them
}

TEST_CASE("StampGate: an input refused for the whole interval is reported until one is taken")
{
    StampGate gate({.max_ahead_us = 2'000'000, .max_age_us = 2'000'000}, 1'000'000);
    const int fix = gate.add_input("GPS_FIX");
    const int imu = gate.add_input("IMU");
    int64_t now = kNow;
    // A refused run shorter than the interval, with good IMU meanwhile: not reported.
    for (int k = 0; k < 5; ++k, now += 200'000) {
        CHECK_FALSE(gate.accept(fix, now + kYear, now));
        CHECK(gate.accept(imu, now, now));
    }
    CHECK(gate.rejecting().empty());
    CHECK(gate.take_change() == ugv::runtime::StampChange::none);
    // The run reaches 1 s: reported, naming the input, and the edge once.
    CHECK_FALSE(gate.accept(fix, now + kYear, now));
    CHECK(gate.rejecting().find("GPS_FIX") != std::string::npos);
    CHECK(gate.take_change() == ugv::runtime::StampChange::rejecting);
    CHECK(gate.take_change() == ugv::runtime::StampChange::none);
    CHECK(gate.rejecting().find("ahead") != std::string::npos);
    now += 200'000;
    CHECK_FALSE(gate.accept(fix, now - kYear, now));
    CHECK(gate.rejecting().find("GPS_FIX") != std::string::npos);
    // One good fix clears it.
    CHECK(gate.accept(fix, now, now));
    CHECK(gate.rejecting().empty());
    CHECK(gate.take_change() == ugv::runtime::StampChange::cleared);
    CHECK(gate.take_change() == ugv::runtime::StampChange::none);
    // One bad message followed by a long silence is not "every message refused".
    CHECK_FALSE(gate.accept(fix, kMax, now));
    now += 10'000'000;
    CHECK(gate.accept(imu, now, now));
    CHECK(gate.rejecting().empty());
}
