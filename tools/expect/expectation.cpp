#include "ugv/expect/expectation.hpp"

#include <cstdio>
#include <stdexcept>

namespace ugv::expect {

void parse_rate(const std::string& text, Expectation& e)
{
    const auto colon = text.find(':');
    if (colon == std::string::npos) throw std::invalid_argument("--rate takes MIN:MAX in Hz (either may be empty)");
    try {
        if (colon > 0) e.rate_min_hz = std::stod(text.substr(0, colon));
        if (colon + 1 < text.size()) e.rate_max_hz = std::stod(text.substr(colon + 1));
    } catch (const std::exception&) {
        throw std::invalid_argument("--rate '" + text + "': not numbers");
    }
    if (e.rate_min_hz && e.rate_max_hz && *e.rate_min_hz > *e.rate_max_hz)
        throw std::invalid_argument("--rate '" + text + "': MIN is above MAX");
}

Verdict judge(const Expectation& e, const Observation& o)
{
    Verdict v;
    v.pass = true;
    char buf[256];
    // The rate over the window the user asked for: what a person watching would count.
    const double rate = e.window_s > 0 ? static_cast<double>(o.stats.count) / e.window_s : 0.0;
    std::snprintf(buf, sizeof buf, "%s: %lld msgs in %.1f s, %.2f Hz", e.channel.c_str(),
                  static_cast<long long>(o.stats.count), e.window_s, rate);
    v.line = buf;
    if (e.rate_min_hz || e.rate_max_hz) {
        const bool ok = (!e.rate_min_hz || rate >= *e.rate_min_hz) && (!e.rate_max_hz || rate <= *e.rate_max_hz);
        std::snprintf(buf, sizeof buf, " [%s, %s] %s", e.rate_min_hz ? std::to_string(*e.rate_min_hz).substr(0, 6).c_str() : "-",
                      e.rate_max_hz ? std::to_string(*e.rate_max_hz).substr(0, 6).c_str() : "-", ok ? "ok" : "FAIL");
        v.line += buf;
        v.pass = v.pass && ok;
    }
    if (e.min_count) {
        const bool ok = o.stats.count >= *e.min_count;
        v.line += ", count >= " + std::to_string(*e.min_count) + (ok ? " ok" : " FAIL");
        v.pass = v.pass && ok;
    }
    if (e.max_gap) {
        const bool ok = o.stats.seq_gaps <= *e.max_gap && o.stats.seq_backwards == 0;
        v.line += ", seq gaps " + std::to_string(o.stats.seq_gaps) + " (max " + std::to_string(*e.max_gap) + ")" +
                  (o.stats.seq_backwards ? ", seq went back " + std::to_string(o.stats.seq_backwards) + "x" : "") +
                  (ok ? " ok" : " FAIL");
        v.pass = v.pass && ok;
    }
    if (e.where) {
        const bool ok = o.where_failed == 0 && o.undecodable == 0;
        v.line += ", where '" + e.where->text() + "': " + std::to_string(o.where_ok) + "/" +
                  std::to_string(o.where_ok + o.where_failed + o.undecodable) + (ok ? " ok" : " FAIL");
        v.pass = v.pass && ok;
    }
    if (o.stats.count == 0) v.pass = false;  // nothing seen is never a pass
    v.line += v.pass ? " -> PASS" : " -> FAIL";
    return v;
}

}  // namespace ugv::expect
