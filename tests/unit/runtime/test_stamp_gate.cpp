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

TEST_CASE("StampGate: stamps ahead of the clock beyond max_stamp_skew_s raise the clock flag at once")
{
    StampGate gate({.max_ahead_us = 2'000'000, .max_age_us = 2'000'000,
                    .skew = {.max_skew_us = 50'000, .max_lag_us = 1'000'000}});
    const int imu = gate.add_input("IMU");
    const int fix = gate.add_input("GPS_FIX");
    int64_t now = kNow;
    // Within the bounds: ahead by up to 50 ms, late by up to 1 s; no flag.
    for (int k = 0; k < 50; ++k, now += 20'000) {
        CHECK(gate.accept(imu, now + (k % 2 == 0 ? 50'000 : -900'000), now));
        CHECK(gate.accept(fix, now - 200'000, now));
    }
    CHECK(gate.counters().clock_skew == 0);
    CHECK(gate.counters().stamps_skewed == 0);
    CHECK(gate.skewed().empty());
    // The IMU's sender is 0.3 s ahead (its messages still taken): flagged by the first one.
    CHECK(gate.accept(imu, now + 300'000 - 2'000, now));
    CHECK(gate.counters().clock_skew == 1);
    CHECK(gate.counters().clock_skew_us == 298'000);
    CHECK(gate.counters().clock_skew_events == 1);
    CHECK(gate.skewed().find("IMU stamped 0.298 s ahead of the clock") != std::string::npos);
    for (int k = 0; k < 10; ++k) {
        now += 20'000;
        CHECK(gate.accept(imu, now + 300'000 - 1'000, now));
    }
    CHECK(gate.counters().clock_skew_us == 299'000);  // the most it was ahead: its sender's clock is at least that
    CHECK(gate.counters().stamps_skewed == 11);
    CHECK(gate.counters().clock_skew_events == 1);
    // Right again: the flag holds for the window after the last early stamp, then clears.
    now += 20'000;
    CHECK(gate.accept(imu, now - 1'000, now));
    CHECK(gate.counters().clock_skew == 1);
    now += StampGate::kSkewWindowUs;
    CHECK(gate.accept(imu, now - 1'000, now));
    CHECK(gate.counters().clock_skew == 0);
    CHECK(gate.counters().clock_skew_us == 0);
    CHECK(gate.skewed().empty());
}

TEST_CASE("StampGate: an input late beyond max_stamp_lag_s is flagged only when every stamp of a window is")
{
    StampGate gate({.max_ahead_us = 2'000'000, .max_age_us = 5'000'000,
                    .skew = {.max_skew_us = 50'000, .max_lag_us = 1'000'000}});
    const int pose = gate.add_input("POSE");
    int64_t now = kNow;
    // Single slow deliveries among good ones: counted, never flagged.
    for (int k = 0; k < 40; ++k, now += 100'000) CHECK(gate.accept(pose, now - (k % 3 == 1 ? 1'500'000 : 400'000), now));
    CHECK(gate.counters().stamps_skewed == 13);
    CHECK(gate.counters().clock_skew == 0);
    // The sender's clock 1.2 s behind: every pose 1.6 s late; flagged once the run spans the window.
    const int64_t start = now;
    while (now - start < StampGate::kSkewWindowUs) {
        CHECK(gate.accept(pose, now - 1'600'000, now));
        CHECK(gate.counters().clock_skew == 0);
        now += 100'000;
    }
    CHECK(gate.accept(pose, now - 1'600'000, now));
    CHECK(gate.counters().clock_skew == 1);
    CHECK(gate.counters().clock_skew_us == -1'600'000);  // at most that far behind
    CHECK(gate.skewed().find("POSE stamped 1.600 s behind the clock") != std::string::npos);
    // One pose within the bound clears it.
    now += 100'000;
    CHECK(gate.accept(pose, now - 400'000, now));
    CHECK(gate.counters().clock_skew == 0);
}

TEST_CASE("StampGate: refused stamps never raise the clock flag; extremes do not overflow")
{
    StampGate gate({.max_ahead_us = 2'000'000, .max_age_us = 2'000'000});
    const int in = gate.add_input("POINTS");
    CHECK_FALSE(gate.accept(in, kMax, kNow));
    CHECK_FALSE(gate.accept(in, kMin, kNow));
    CHECK(gate.counters().clock_skew == 0);
    StampGate wide({.max_ahead_us = kMax, .max_age_us = kMax});
    const int w = wide.add_input("POINTS");
    CHECK(wide.accept(w, kMax, 0));
    CHECK(wide.counters().clock_skew_us == kMax);
    CHECK(wide.counters().clock_skew == 1);
    CHECK(wide.accept(w, 0, kMax));  // a window later and 2^63 late: early over, the late run only begun
    CHECK(wide.counters().clock_skew == 0);
}

TEST_CASE("max_stamp_skew_s and max_stamp_lag_s: defaults, values and one-line errors")
{
    using ugv::runtime::Config;
    using ugv::runtime::ConfigError;
    Config empty = Config::empty();
    const auto d = ugv::runtime::read_stamp_skew_limits(empty, 2'000'000);
    CHECK(d.max_skew_us == 50'000);
    CHECK(d.max_lag_us == 1'000'000);
    Config set = Config::parse("max_stamp_skew_s = 0.002\nmax_stamp_lag_s = 0.5\n", "pose.toml");
    const auto s = ugv::runtime::read_stamp_skew_limits(set, 2'000'000);
    CHECK(s.max_skew_us == 2'000);
    CHECK(s.max_lag_us == 500'000);
    const auto error_of = [](const std::string& text) {
        try {
            Config c = Config::parse(text, "pose.toml");
            ugv::runtime::read_stamp_skew_limits(c, 2'000'000);
        } catch (const ConfigError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    CHECK(error_of("max_stamp_skew_s = 3\n") == "pose.toml: max_stamp_skew_s: must not exceed max_stamp_ahead_s");
    CHECK(error_of("max_stamp_lag_s = -1\n").rfind("pose.toml: max_stamp_lag_s: ", 0) == 0);
    CHECK(error_of("max_stamp_skew_s = \"x\"\n").rfind("pose.toml: max_stamp_skew_s: ", 0) == 0);
}
