#include "attitude_command.hpp"

#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

#include "attitude_error.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/pose_t.hpp"
#include "ugv/sim_truth_t.hpp"

namespace ugv::eval {

namespace {

struct Stamped
{
    int64_t utime;
    double roll, pitch, yaw;
};

}  // namespace

AttitudeCommand::AttitudeCommand(CLI::App& app)
    : sub_(app.add_subcommand("attitude", "roll/pitch/yaw error of the IMU's output and of the pose against SIM_TRUTH"))
{
    sub_->add_option("log", log_, "LCM log with sim_truth_t and imu_t and/or pose_t")->required()->check(CLI::ExistingFile);
    sub_->add_option("--imu-channel", imu_channel_, "imu_t channel");
    sub_->add_option("--pose-channel", pose_channel_, "pose_t channel");
    sub_->add_option("--pose-log", pose_log_, "take the pose from this log instead (e.g. ugv-pose --replay LOG --out LOG2)")
        ->check(CLI::ExistingFile);
    sub_->add_option("--truth-channel", truth_channel_, "sim_truth_t channel");
    sub_->add_option("--turn-rate", turn_rate_dps_, "a true yaw rate above this is turning (deg/s)")
        ->check(CLI::Range(0.01, 90.0));
    sub_->add_option("--standing-speed", standing_speed_mps_, "a true speed below this (not turning) is standing (m/s)")
        ->check(CLI::Range(0.0, 10.0));
}

int AttitudeCommand::run() const
{
    std::vector<TruthSample> truth;
    std::vector<Stamped> imu, pose;
    uint64_t malformed = 0, pose_not_ok = 0;
    sim_truth_t t{};
    imu_t i{};
    pose_t p{};
    // With --pose-log the pose comes from there alone, the truth and the IMU from LOG.
    for (int pass = 0; pass < 2; ++pass) {
        const std::string& file = pass == 0 ? log_ : pose_log_;
        if (file.empty()) continue;
        lcm::LogFile log(file, "r");
        if (!log.good()) {
            std::fprintf(stderr, "ugv-eval: %s: not an LCM log\n", file.c_str());
            return 2;
        }
        const bool pose_only = pass == 1;
        const bool pose_here = pose_log_.empty() || pose_only;
        while (const lcm::LogEvent* ev = log.readNextEvent()) {
            const auto n = static_cast<std::size_t>(ev->datalen);
            if (pose_only && ev->channel != pose_channel_) continue;
            if (ev->channel == truth_channel_) {
                if (!bus::decode_checked(ev->data, n, t)) {
                    ++malformed;
                    continue;
                }
                truth.push_back({t.utime, t.roll, t.pitch, t.yaw, std::hypot(t.velocity[0], t.velocity[1])});
            } else if (ev->channel == imu_channel_) {
                if (!bus::decode_checked(ev->data, n, i)) {
                    ++malformed;
                    continue;
                }
                if ((i.valid & imu_t::VALID_EULER) != 0) imu.push_back({i.utime, i.roll, i.pitch, i.yaw});
            } else if (ev->channel == pose_channel_ && pose_here) {
                if (!bus::decode_checked(ev->data, n, p)) {
                    ++malformed;
                    continue;
                }
                // Not yet initialised or failed: no attitude to judge.
                if (p.status == pose_t::STATUS_INITIALIZING || p.status == pose_t::STATUS_FAULT) {
                    ++pose_not_ok;
                    continue;
                }
                pose.push_back({p.utime, p.roll, p.pitch, p.yaw});
            }
        }
    }
    if (malformed > 0) std::fprintf(stderr, "ugv-eval: %llu malformed message(s) skipped\n", static_cast<unsigned long long>(malformed));
    if (truth.empty()) {
        std::fprintf(stderr, "ugv-eval: no %s in %s: a simulated run's log is needed\n", truth_channel_.c_str(), log_.c_str());
        return 1;
    }
    const TruthTrack track(std::move(truth));
    AttitudeRules rules;
    rules.turn_rate_radps = turn_rate_dps_ * 3.14159265358979323846 / 180.0;
    rules.standing_speed_mps = standing_speed_mps_;
    bool any = false;
    for (const auto& [name, samples] : {std::pair{imu_channel_, &imu}, std::pair{pose_channel_, &pose}}) {
        AttitudeErrors e(track, rules);
        for (const Stamped& s : *samples) e.add(s.utime, s.roll, s.pitch, s.yaw);
        if (e.all().samples == 0) continue;
        any = true;
        for (int m = 0; m < 3; ++m) std::printf("%s\n", json_line(name, kMotionNames[m], e.of(static_cast<Motion>(m))).c_str());
        std::printf("%s\n", json_line(name, "all", e.all()).c_str());
        if (e.unscored() > 0)
            std::fprintf(stderr, "ugv-eval: %s: %llu sample(s) outside the truth's time span, not scored\n", name.c_str(),
                         static_cast<unsigned long long>(e.unscored()));
    }
    if (pose_not_ok > 0)
        std::fprintf(stderr, "ugv-eval: %s: %llu pose(s) initialising or in fault, not scored\n", pose_channel_.c_str(),
                     static_cast<unsigned long long>(pose_not_ok));
    if (!any) {
        std::fprintf(stderr, "ugv-eval: nothing on %s or %s within the truth's time span in %s\n", imu_channel_.c_str(),
                     pose_channel_.c_str(), log_.c_str());
        return 1;
    }
    return 0;
}

}  // namespace ugv::eval
