// What the ugv-lms integration tests share: a listener on the test's LCM port (scans, status,
// raw bytes), the emulator started on a pty, the daemon's config, and the emulator's floor
// (`--height 1.0 --pitch-deg 10`) as the known answer every published scan must equal, and
// the test of whether a damaged scan could have been refused at all.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <ugv/daemon_status_t.hpp>
#include <ugv/laser_scan_t.hpp>
#include <ugv/raw_bytes_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/sick_lms2xx/crc.hpp"
#include "ugv/sick_lms2xx/scan.hpp"
#include "ugv_test/process.hpp"

namespace ugv::test::lms {

constexpr double kPi = 3.14159265358979323846;

class Listener
{
public:
    explicit Listener(const std::string& url) : bus_(ugv::bus::open_live(url))
    {
        ugv::bus::subscribe<ugv::laser_scan_t>(*bus_, "LMS_SCAN",
                                               [this](const std::string&, const ugv::laser_scan_t& m, int64_t recv) {
                                                   scans.push_back(m);
                                                   recv_utime.push_back(recv);
                                               });
        ugv::bus::subscribe<ugv::daemon_status_t>(*bus_, "STATUS_LMS",
                                                  [this](const std::string&, const ugv::daemon_status_t& m, int64_t) {
                                                      status = m;
                                                      ++statuses;
                                                      seen_states.push_back(m.state);
                                                  });
        ugv::bus::subscribe<ugv::raw_bytes_t>(*bus_, "RAW_LMS", [this](const std::string&, const ugv::raw_bytes_t& m, int64_t) {
            if (m.direction == ugv::raw_bytes_t::DIRECTION_TO_DEVICE)
                raw_to_device.insert(raw_to_device.end(), m.data.begin(), m.data.end());
            else
                raw_from_device += m.data.size();
        });
    }
    template <typename Pred>
    bool until(Pred pred, double timeout_s)
    {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (!pred() && std::chrono::steady_clock::now() < end) bus_->handle(20);
        return pred();
    }
    void for_seconds(double s)
    {
        until([] { return false; }, s);
    }
    int64_t counter(const std::string& name) const
    {
        for (int i = 0; i < status.ncounters; ++i)
            if (status.counter_names[static_cast<std::size_t>(i)] == name)
                return status.counter_values[static_cast<std::size_t>(i)];
        return -1;
    }
    bool saw_state(int8_t state) const
    {
        return std::find(seen_states.begin(), seen_states.end(), state) != seen_states.end();
    }

    std::vector<ugv::laser_scan_t> scans;
    std::vector<int64_t> recv_utime;
    ugv::daemon_status_t status{};
    int statuses = 0;
    std::vector<int8_t> seen_states;
    std::vector<uint8_t> raw_to_device;
    std::size_t raw_from_device = 0;

private:
    std::unique_ptr<ugv::bus::Bus> bus_;
};

inline std::unique_ptr<Process> start_emulator(const TempDir& dir, const std::string& pty, const std::string& tag,
                                               std::vector<std::string> extra = {})
{
    std::vector<std::string> args = {bin("ugv-sim"), "lms", "--pty", pty, "--height", "1.0", "--pitch-deg", "10"};
    args.insert(args.end(), extra.begin(), extra.end());
    auto p = std::make_unique<Process>(args, dir / ("sim-" + tag + ".out"), dir / ("sim-" + tag + ".err"));
    REQUIRE(wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    return p;
}

inline std::string config_text(const std::string& pty, const std::string& extra = "",
                               const std::string& variant = "angle_deg = 180\nresolution_deg = 0.5\n")
{
    return "device = \"" + pty + "\"\nbaud = 500000\n" + variant + "units = \"mm\"\nsensor_id = \"front\"\n" + extra;
}

inline bool contains(const std::vector<uint8_t>& hay, const std::vector<uint8_t>& needle)
{
    return std::search(hay.begin(), hay.end(), needle.begin(), needle.end()) != hay.end();
}

// The range codes of the emulator's floor (`--height 1.0 --pitch-deg 10`) for a scan of this
// layout, computed as the emulator does (mm units).
inline std::vector<uint16_t> floor_codes(const ugv::laser_scan_t& s)
{
    const long res_cdeg = std::lround(static_cast<double>(s.angle_increment) * 180.0 / kPi * 100.0);
    const long angle_deg = res_cdeg * (s.nranges - 1) / 100;
    std::vector<uint16_t> codes(static_cast<std::size_t>(s.nranges));
    for (int i = 0; i < s.nranges; ++i) {
        const double deg = -static_cast<double>(angle_deg) / 2.0 + static_cast<double>(i * res_cdeg) / 100.0;
        const double down = std::cos(deg * kPi / 180.0) * std::sin(10.0 * kPi / 180.0);
        const double range_m = down <= 1e-9 ? std::numeric_limits<double>::infinity() : 1.0 / down;
        codes[static_cast<std::size_t>(i)] = ugv::sick_lms2xx::encode_range(range_m, ugv::sick_lms2xx::Units::mm);
    }
    return codes;
}

// The codes a published scan stands for: mm for a range; the emulator's only special code
// (8183, no echo) for NaN + FLAG_OVERFLOW; anything else is not what the emulator sends.
inline std::vector<int> published_codes(const ugv::laser_scan_t& s)
{
    std::vector<int> codes(s.ranges.size());
    for (std::size_t i = 0; i < s.ranges.size(); ++i) {
        if (std::isfinite(s.ranges[i]) && s.flags[i] == ugv::laser_scan_t::FLAG_OK)
            codes[i] = static_cast<int>(std::lround(static_cast<double>(s.ranges[i]) * 1000.0));
        else
            codes[i] = s.flags[i] == ugv::laser_scan_t::FLAG_OVERFLOW ? 8183 : -1;
    }
    return codes;
}

// Whether a scan is the emulator's floor, beam for beam, exactly: empty when it is, else the
// first beam that differs.
inline std::string floor_mismatch(const ugv::laser_scan_t& s)
{
    if (s.nranges < 2 || static_cast<std::size_t>(s.nranges) != s.ranges.size()) return "bad count";
    const std::vector<uint16_t> want = floor_codes(s);
    const std::vector<int> got = published_codes(s);
    for (std::size_t i = 0; i < want.size(); ++i)
        if (got[i] != want[i])
            return "beam " + std::to_string(i) + ": code " + std::to_string(got[i]) + ", want " + std::to_string(want[i]);
    return "";
}

// Whether the damage in a scan is invisible to the LMS checksum (so no receiver could have
// refused it). The checksum of the fact sheet starts at 0 and is linear over GF(2): a damaged
// telegram passes exactly when the checksum of the error pattern alone (the XOR of intact
// and damaged telegrams: zeros, then the XOR of each value word) is 0. Flipping bit b of one
// byte and bit b + 1 of the next (b < 7) is such a pattern.
inline bool damage_invisible_to_checksum(const ugv::laser_scan_t& s)
{
    constexpr std::size_t kValuesAt = 7;  // STX, ADDR, LEN (2), CMD, count word (2)
    const std::vector<uint16_t> want = floor_codes(s);
    const std::vector<int> got = published_codes(s);
    std::vector<uint8_t> pattern(kValuesAt + 2 * want.size() + 1, 0);  // + STATUS
    for (std::size_t i = 0; i < want.size(); ++i) {
        if (got[i] < 0) return false;  // a code the emulator never sends: not a flip of its value
        const auto x = static_cast<uint16_t>(static_cast<unsigned>(got[i]) ^ want[i]);
        pattern[kValuesAt + 2 * i] = static_cast<uint8_t>(x & 0xff);
        pattern[kValuesAt + 2 * i + 1] = static_cast<uint8_t>(x >> 8);
    }
    return ugv::sick_lms2xx::crc16(pattern.data(), pattern.size()) == 0;
}

}  // namespace ugv::test::lms
