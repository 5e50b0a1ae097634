// The LMS 2xx models the driver accepts, told apart by the type string the device answers to
// 3A ("LMS291;S05"). They share the telegrams, the variants (100/180 deg, 0.25/0.5/1 deg),
// the 8/80 m measuring mode and the mm/cm units the session sets; they differ in housing
// (211/221/291 outdoor), firmware and the length of the configuration block, which the
// session echoes back whole. A type string it does not know is logged and handled as an
// LMS 2xx: the handshake itself tells whether the device speaks the protocol.
#pragma once

#include <optional>
#include <string_view>

namespace ugv::sick_lms2xx {

// 200, 211, 220, 221 or 291 from "LMS<n>" at the start of the type string; nullopt otherwise.
std::optional<int> model_from_type(std::string_view type);

}  // namespace ugv::sick_lms2xx
