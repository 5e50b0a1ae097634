#include "ugv/novatel/fix_quality.hpp"

#include "ugv/novatel/enums.hpp"

namespace ugv::novatel {

const char* fix_quality_name(FixQuality q)
{
    switch (q) {
    case FixQuality::none: return "NONE";
    case FixQuality::single: return "SINGLE";
    case FixQuality::sbas: return "SBAS";
    case FixQuality::dgps: return "DGPS";
    case FixQuality::rtk_float: return "RTK_FLOAT";
    case FixQuality::rtk_fixed: return "RTK_FIXED";
    case FixQuality::dead_reckoning: return "DEAD_RECKONING";
    case FixQuality::unknown: return "UNKNOWN";
    }
    return "UNKNOWN";
}

FixQuality quality_from_position_type(uint32_t solution_status, uint32_t position_type)
{
    if (solution_status != solution_status::sol_computed) {
        return FixQuality::none;
    }
    switch (position_type) {
    case 0:   // NONE
    case 8:   // DOPPLER_VELOCITY: a velocity, no position
        return FixQuality::none;
    case 16:  // SINGLE
    case 53:  // INS_PSRSP
    case 68:  // PPP_CONVERGING: still metre-level
        return FixQuality::single;
    case 18:  // WAAS
        return FixQuality::sbas;
    case 17:  // PSRDIFF
    case 20:  // OMNISTAR (VBS)
    case 54:  // INS_PSRDIFF
    case 64:  // OMNISTAR_HP
    case 65:  // OMNISTAR_XP
    case 66:  // CDGPS
    case 69:  // PPP
        return FixQuality::dgps;
    case 4:   // FLOATCONV
    case 32:  // L1_FLOAT
    case 33:  // IONOFREE_FLOAT
    case 34:  // NARROW_FLOAT
    case 55:  // INS_RTKFLOAT
        return FixQuality::rtk_float;
    case 5:   // WIDELANE
    case 6:   // NARROWLANE
    case 48:  // L1_INT
    case 49:  // WIDE_INT
    case 50:  // NARROW_INT
    case 51:  // RTK_DIRECT_INS
    case 56:  // INS_RTKFIXED
        return FixQuality::rtk_fixed;
    case 19:  // PROPAGATED
    case 52:  // INS
        return FixQuality::dead_reckoning;
    default:  // FIXEDPOS, FIXEDHEIGHT, and values newer than our tables
        return FixQuality::unknown;
    }
}

FixQuality quality_from_gga(int q)
{
    switch (q) {
    case 0: return FixQuality::none;
    case 1: return FixQuality::single;
    case 2: return FixQuality::dgps;
    case 4: return FixQuality::rtk_fixed;
    case 5: return FixQuality::rtk_float;
    case 6: return FixQuality::dead_reckoning;
    case 9: return FixQuality::sbas;
    default: return FixQuality::unknown;  // 3 PPS, 7 fixed position, 8 simulator, others
    }
}

}  // namespace ugv::novatel
