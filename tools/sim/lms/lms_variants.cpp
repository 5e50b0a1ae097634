#include "lms_variants.hpp"

#include <algorithm>
#include <stdexcept>

namespace ugv::sim::lms {

const std::vector<Variant>& variants()
{
    // Type strings: model and firmware as the 3A reply carries them ("LMS200;30106").
    // Config block lengths cover both ends of the fact sheet's 32-42 bytes; an outdoor unit
    // left by its last user in the 32 m mode makes the driver write the 8/80 m mode back.
    static const std::vector<Variant> all = {
        {"LMS200", "LMS200;30106", "V02.10 ", 30, 32, 0x00, 0x00, {0x00, 0x06}, false},
        {"LMS211", "LMS211;30206", "V02.30 ", 34, 35, 0x00, 0x00, {0x00, 0x06}, true},
        {"LMS220", "LMS220;30106", "V02.10 ", 30, 32, 0x01, 0x00, {0x00, 0x06}, false},
        {"LMS221", "LMS221;30206", "V02.30 ", 34, 35, 0x01, 0x06, {0x00, 0x06}, true},
        {"LMS291", "LMS291;S05", "V02.61 ", 40, 42, 0x00, 0x06, {0x00, 0x06}, true},
    };
    return all;
}

std::string variant_names()
{
    std::string s;
    for (const auto& v : variants()) s += (s.empty() ? "" : ", ") + v.name;
    return s;
}

const Variant& find_variant(const std::string& name)
{
    for (const auto& v : variants())
        if (v.name == name || v.name == "LMS" + name) return v;
    throw std::invalid_argument("--variant: '" + name + "' is not one of " + variant_names());
}

std::vector<uint8_t> status_block(const Variant& v, bool streaming)
{
    std::vector<uint8_t> s(v.software_version.begin(), v.software_version.end());
    s.push_back(streaming ? 0x24 : 0x25);
    s.resize(std::max(v.status_bytes, s.size()), 0x00);
    return s;
}

}  // namespace ugv::sim::lms
