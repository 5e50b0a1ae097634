#include "fault_spec.hpp"

#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace ugv::sim::lms {

namespace {

std::vector<std::string> split(const std::string& s)
{
    std::vector<std::string> parts;
    std::size_t at = 0;
    for (std::size_t colon; (colon = s.find(':', at)) != std::string::npos; at = colon + 1) parts.push_back(s.substr(at, colon - at));
    parts.push_back(s.substr(at));
    return parts;
}

double number(const std::string& spec, const std::string& text, double min, double max)
{
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end == nullptr || *end != '\0' || !(v >= min && v <= max))
        throw std::invalid_argument("--fault " + spec + ": '" + text + "' is not a number in [" + std::to_string(min) +
                                    ", " + std::to_string(max) + "]");
    return v;
}

}  // namespace

void add_fault(const std::string& spec, FaultPlan& plan)
{
    const std::vector<std::string> p = split(spec);
    const std::string& name = p[0];
    const auto arg = [&](std::size_t i, double def, double min, double max) {
        return p.size() > i ? number(spec, p[i], min, max) : def;
    };
    std::size_t max_args = 1;
    if (name == "garbage") {
        plan.device.garbage_probability = arg(1, 0.1, 0.0, 1.0);
    } else if (name == "bitflip") {
        plan.device.bitflip_probability = arg(1, 0.05, 0.0, 1.0);
    } else if (name == "ber") {
        plan.device.bit_error_rate = arg(1, 1e-3, 0.0, 1.0);
    } else if (name == "truncate") {
        plan.device.truncate_probability = arg(1, 0.1, 0.0, 1.0);
    } else if (name == "silence") {
        plan.device.silence_every_s = arg(1, 5.0, 0.1, 3600.0);
        plan.device.silence_for_s = arg(2, 1.0, 0.01, plan.device.silence_every_s);
        max_args = 2;
    } else if (name == "disappear") {
        plan.disappear_after_s = arg(1, 5.0, 0.1, 3600.0);
        plan.disappear_for_s = arg(2, 1.0, 0.0, 3600.0);
        max_args = 2;
    } else {
        throw std::invalid_argument("--fault " + spec + ": unknown fault (garbage, bitflip, ber, truncate, silence, disappear)");
    }
    if (p.size() > max_args + 1) throw std::invalid_argument("--fault " + spec + ": too many values");
}

}  // namespace ugv::sim::lms
