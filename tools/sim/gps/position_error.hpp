// The receiver's position error as a first-order Gauss-Markov process per class of position
// type (RTK fixed, RTK float, DGPS, SBAS, single): each class has its own process (its sigma
// and correlation time), so the solution jumps when the type changes (fixed -> float ->
// DGPS) and returns to the old class's slowly moving error when it changes back. The sigma
// the receiver reports is the class's: the true spread of that error. No I/O; time passed in.
#pragma once

#include <array>
#include <cstdint>
#include <random>

namespace ugv::sim::gps {

enum class FixClass { rtk_fixed, rtk_float, dgps, sbas, single, other };
inline constexpr std::size_t kFixClasses = 6;
FixClass fix_class_of(uint32_t position_type);
const char* fix_class_name(FixClass c);  // "rtk_fixed" ... "other": the scenario's key prefixes

struct Ned3
{
    double north_m = 0, east_m = 0, up_m = 0;
};

struct ClassError
{
    double sigma_m;          // horizontal 1-sigma per axis (north, east); height 1.5x
    double time_constant_s;  // correlation time of the Gauss-Markov process
};

struct PositionErrorConfig
{
    // Indexed by FixClass. Sigmas as the white model's (sigma_of); time constants: multipath
    // for the carrier-phase solutions (tens of seconds), atmosphere and orbits for the
    // code solutions (minutes).
    std::array<ClassError, kFixClasses> classes{{{0.02, 30.0},
                                                 {0.15, 60.0},
                                                 {0.4, 60.0},
                                                 {0.8, 120.0},
                                                 {1.5, 120.0},
                                                 {10.0, 120.0}}};
    double scale = 1.0;  // x every sigma (the scenario's noise_scale)
    uint32_t seed = 1;
};

class PositionErrorModel
{
public:
    explicit PositionErrorModel(const PositionErrorConfig& config);
    // The error (north, east, up; m) of a fix of this position type at utime. Times must not
    // go back; asking twice at one time gives the same error.
    Ned3 at(int64_t utime, uint32_t position_type);
    // The 1-sigma the receiver reports for the type: horizontal (per axis) and height.
    double sigma_horizontal_m(uint32_t position_type) const;
    double sigma_height_m(uint32_t position_type) const { return 1.5 * sigma_horizontal_m(position_type); }

private:
    struct Process
    {
        bool started = false;
        int64_t utime = 0;
        std::array<double, 3> error{};  // north, east, up in units of the class's sigmas
    };
    PositionErrorConfig config_;
    std::array<Process, kFixClasses> processes_{};
    std::mt19937 rng_;
    std::normal_distribution<double> gauss_{0.0, 1.0};
};

}  // namespace ugv::sim::gps
