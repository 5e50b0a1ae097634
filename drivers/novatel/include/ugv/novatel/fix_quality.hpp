// What a receiver's position type (or an NMEA GGA quality) means for a user of the fix.
#pragma once

#include <cstdint>

namespace ugv::novatel {

// Same numbering as gps_fix_t.QUALITY_*.
enum class FixQuality : int8_t {
    none = 0,            // no position (or the solution was not computed)
    single = 1,          // stand-alone code solution
    sbas = 2,            // SBAS (WAAS/EGNOS) corrected
    dgps = 3,            // code differential (PSRDIFF, OmniSTAR VBS/HP/XP, CDGPS, PPP)
    rtk_float = 4,
    rtk_fixed = 5,
    dead_reckoning = 6,  // propagated / INS only
    unknown = 7,         // a valid solution of a kind we do not classify (incl. unknown enums,
                         // and FIXEDPOS/FIXEDHEIGHT, which are entered, not measured)
};

const char* fix_quality_name(FixQuality q);

// From BESTPOS/PSRPOS: anything but SOL_COMPUTED is `none`.
FixQuality quality_from_position_type(uint32_t solution_status, uint32_t position_type);
// From the GGA quality field (OEM4 meanings, see the fact sheet).
FixQuality quality_from_gga(int gga_quality);

}  // namespace ugv::novatel
