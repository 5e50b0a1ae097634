#include "ugv/novatel/enums.hpp"

#include <span>

namespace ugv::novatel {
namespace {

struct Entry
{
    uint32_t value;
    std::string_view name;
};

constexpr Entry kSolutionStatus[] = {
    {0, "SOL_COMPUTED"}, {1, "INSUFFICIENT_OBS"}, {2, "NO_CONVERGENCE"}, {3, "SINGULARITY"},
    {4, "COV_TRACE"},    {5, "TEST_DIST"},        {6, "COLD_START"},     {7, "V_H_LIMIT"},
    {8, "VARIANCE"},     {9, "RESIDUALS"},        {10, "DELTA_POS"},     {11, "NEGATIVE_VAR"},
    {13, "INTEGRITY_WARNING"}, {18, "PENDING"},   {19, "INVALID_FIX"},   {20, "UNAUTHORIZED"},
};

constexpr Entry kPositionType[] = {
    {0, "NONE"},           {1, "FIXEDPOS"},        {2, "FIXEDHEIGHT"},    {4, "FLOATCONV"},
    {5, "WIDELANE"},       {6, "NARROWLANE"},      {8, "DOPPLER_VELOCITY"}, {16, "SINGLE"},
    {17, "PSRDIFF"},       {18, "WAAS"},           {19, "PROPAGATED"},    {20, "OMNISTAR"},
    {32, "L1_FLOAT"},      {33, "IONOFREE_FLOAT"}, {34, "NARROW_FLOAT"},  {48, "L1_INT"},
    {49, "WIDE_INT"},      {50, "NARROW_INT"},     {51, "RTK_DIRECT_INS"}, {52, "INS"},
    {53, "INS_PSRSP"},     {54, "INS_PSRDIFF"},    {55, "INS_RTKFLOAT"},  {56, "INS_RTKFIXED"},
    {64, "OMNISTAR_HP"},   {65, "OMNISTAR_XP"},    {66, "CDGPS"},         {68, "PPP_CONVERGING"},
    {69, "PPP"},
};

constexpr Entry kTimeStatus[] = {
    {20, "UNKNOWN"},          {60, "APPROXIMATE"},   {80, "COARSEADJUSTING"}, {100, "COARSE"},
    {120, "COARSESTEERING"},  {130, "FREEWHEELING"}, {140, "FINEADJUSTING"},  {160, "FINE"},
    {170, "FINEBACKUPSTEERING"}, {180, "FINESTEERING"}, {200, "SATTIME"},
};

std::optional<std::string_view> name_of(std::span<const Entry> table, uint32_t value)
{
    for (const auto& e : table) {
        if (e.value == value) {
            return e.name;
        }
    }
    return std::nullopt;
}

uint32_t value_of(std::span<const Entry> table, std::string_view name)
{
    for (const auto& e : table) {
        if (e.name == name) {
            return e.value;
        }
    }
    return kUnknownEnum;
}

}  // namespace

std::optional<std::string_view> solution_status_name(uint32_t v) { return name_of(kSolutionStatus, v); }
std::optional<std::string_view> position_type_name(uint32_t v) { return name_of(kPositionType, v); }
std::optional<std::string_view> time_status_name(uint32_t v) { return name_of(kTimeStatus, v); }
uint32_t solution_status_from_name(std::string_view n) { return value_of(kSolutionStatus, n); }
uint32_t position_type_from_name(std::string_view n) { return value_of(kPositionType, n); }
uint32_t time_status_from_name(std::string_view n) { return value_of(kTimeStatus, n); }

}  // namespace ugv::novatel
