// Any bytes as a daemon's config file: either a ConfigError (one line) or values within the
// ranges asked for; a channel name or regex that is returned passes its own check (so the
// regex compilers saw it and did not crash). Never a crash, never another exception.
#include <cstdlib>
#include <string>

#include "ugv/runtime/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        auto c = ugv::runtime::Config::parse(text, "fuzz.toml");
        c.get_string("device", "/dev/ttyUSB0");
        const auto baud = c.get_int("baud", 500000, {9600, 19200, 38400, 500000});
        const double h = c.get_double("height_m", 0.87, 0.0, 5.0);
        c.get_enum("units", "mm", {"mm", "cm"});
        c.get_bool("publish_raw", false);
        c.get_doubles("offset_m", {0, 0, 0}, 3, -10, 10);
        c.get_strings("logs", {});
        const std::string channel = c.get_channel("channel", "LMS_SCAN");
        const std::string pattern = c.get_channel_regex("points_channel", "POINTS.*");
        if (!ugv::runtime::Config::channel_name_problem(channel).empty() || channel.size() > 63) std::abort();
        if (!ugv::runtime::Config::channel_regex_problem(pattern).empty()) std::abort();
        auto s = c.section("mount");
        s.get_double("tilt_deg", 0, -90, 90);
        c.finish();
        (void)c.effective_toml();
        if (h < 0.0 || h > 5.0 || (baud != 9600 && baud != 19200 && baud != 38400 && baud != 500000)) std::abort();
    } catch (const ugv::runtime::ConfigError& e) {
        if (std::string(e.what()).find('\n') != std::string::npos && e.key() != "-") std::abort();
    }
    return 0;
}
