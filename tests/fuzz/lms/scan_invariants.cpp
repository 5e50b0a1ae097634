#include "scan_invariants.hpp"

#include <cmath>
#include <cstdlib>

#include "ugv/sick_lms2xx/replies.hpp"
#include "ugv/sick_lms2xx/scan.hpp"

namespace ugv::fuzz {
namespace {

void require(bool ok)
{
    if (!ok) std::abort();
}

void check_scan(const sick_lms2xx::Scan& s)
{
    using namespace sick_lms2xx;
    const std::size_t n = s.ranges_m.size();
    require(n <= (kMaxLen - 4) / 2);  // CMD + STATUS + COUNT take 4 of LEN's bytes
    require(s.flags.size() == n && s.fields.size() == n);
    require(s.partial_index >= 0 && s.partial_index <= 3);
    require(s.units == Units::cm || s.units == Units::mm);
    const double max_m = range_max_m(s.units);
    for (std::size_t i = 0; i < n; ++i) {
        const bool ok = s.flags[i] == static_cast<int8_t>(BeamFlag::ok);
        require(ok != std::isnan(s.ranges_m[i]));
        if (ok) require(s.ranges_m[i] >= 0.0f && s.ranges_m[i] <= static_cast<float>(max_m) * 1.0001f);
        require(s.flags[i] >= 0 && s.flags[i] <= static_cast<int8_t>(BeamFlag::other));
        require(s.fields[i] <= 7);
    }
    require(s.scan_index >= -1 && s.scan_index <= 0xffff);
}

}  // namespace

void check_telegram(const sick_lms2xx::Telegram& t)
{
    using namespace sick_lms2xx;
    require(t.raw.size() >= kHeaderBytes + 1 + kCrcBytes && t.raw.size() <= kHeaderBytes + kMaxLen + kCrcBytes);
    require(t.data.data() >= t.raw.data() && t.data.data() + t.data.size() <= t.raw.data() + t.raw.size());

    Scan scan;
    if (decode_scan(t, scan) == ScanError::none) check_scan(scan);
    if (auto config = decode_config_reply(t)) {
        require(config->block.size() >= kConfigMinBytes);
        (void)config->availability();
        (void)config->measuring_mode();
        (void)config->units();
    }
    (void)decode_mode_reply(t);
    (void)decode_variant_reply(t);
    (void)decode_write_config_reply(t);
    if (auto type = decode_type_reply(t)) {
        for (const char c : *type) require(c >= 0x20 && c < 0x7f);
    }
    (void)decode_status_reply(t);
    (void)is_reset_reply(t);
}

}  // namespace ugv::fuzz
