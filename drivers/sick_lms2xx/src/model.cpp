#include "ugv/sick_lms2xx/model.hpp"

#include <array>
#include <cctype>

namespace ugv::sick_lms2xx {

std::optional<int> model_from_type(std::string_view type)
{
    constexpr std::array<int, 5> kModels = {200, 211, 220, 221, 291};
    if (type.size() < 6 || type.substr(0, 3) != "LMS") return std::nullopt;
    int n = 0;
    for (std::size_t i = 3; i < 6; ++i) {
        if (!std::isdigit(static_cast<unsigned char>(type[i]))) return std::nullopt;
        n = n * 10 + (type[i] - '0');
    }
    // "LMS2910" is not an LMS 291: the number ends at a separator or the end.
    if (type.size() > 6 && std::isdigit(static_cast<unsigned char>(type[6]))) return std::nullopt;
    for (const int m : kModels)
        if (m == n) return n;
    return std::nullopt;
}

}  // namespace ugv::sick_lms2xx
