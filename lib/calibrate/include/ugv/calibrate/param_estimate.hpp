// One estimated parameter of a calibration, as every ugv-calibrate command reports it.
#pragma once

namespace ugv::calibrate {

struct ParamEstimate
{
    double initial = 0;   // rad or m
    double value = 0;     // the estimate (the initial value when not determined)
    double sigma = 0;     // 1-sigma: the larger of the formal one and the spread over blocks;
                          // infinite for one the data says nothing about
    bool determined = false;
};

}  // namespace ugv::calibrate
