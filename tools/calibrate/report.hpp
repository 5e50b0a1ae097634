// What every ugv-calibrate command prints of one estimated parameter: a JSON member and a
// text line (value, sigma, the configured value, or why it is not determined).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include "ugv/calibrate/param_estimate.hpp"

namespace ugv::calibrate_tool {

// `"NAME": {"value": .., "sigma": ..|null, "initial": .., "determined": ..}`, each x scale.
inline std::string json_param(const std::string& name, const calibrate::ParamEstimate& e, double scale)
{
    char sigma[32] = "null";
    if (std::isfinite(e.sigma)) std::snprintf(sigma, sizeof sigma, "%.5f", e.sigma * scale);
    char buf[256];
    std::snprintf(buf, sizeof buf, "\"%s\": {\"value\": %.5f, \"sigma\": %s, \"initial\": %.5f, \"determined\": %s}",
                  name.c_str(), e.value * scale, sigma, e.initial * scale, e.determined ? "true" : "false");
    return buf;
}

// "  NAME  value UNIT +- sigma  (configured c)" or "  NAME  not determined: WHY; the
// configured c UNIT is kept".
inline void print_param(const char* name, const calibrate::ParamEstimate& e, double scale, const char* unit,
                        const std::string& why_not)
{
    if (e.determined)
        std::printf("  %-6s %9.4f %s +- %.4f  (configured %.4f)\n", name, e.value * scale, unit, e.sigma * scale,
                    e.initial * scale);
    else
        std::printf("  %-6s not determined: %s; the configured %.4f %s is kept\n", name, why_not.c_str(),
                    e.initial * scale, unit);
}

}  // namespace ugv::calibrate_tool
