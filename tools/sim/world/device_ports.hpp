// The four emulated devices of the simulated vehicle, each on its own pseudo-terminal and fed
// from the one World: the bytes the host writes go to the device model, the model's bytes go
// back, and every measurement comes from the World's truth at the time it is made.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "gps_emulator.hpp"
#include "imu_emulator.hpp"
#include "lms_emulator.hpp"
#include "servo_emulator.hpp"
#include "slcan_adapter.hpp"
#include "ugv/io/pty.hpp"
#include "ugv/simworld/world.hpp"

namespace ugv::sim::world {

// A device behind a pty: poll its master fd for input, then call service() with the time.
class DevicePort
{
public:
    explicit DevicePort(const std::string& link_path) : pty_(link_path) {}
    virtual ~DevicePort() = default;
    int fd() const { return pty_.master_fd(); }
    const std::string& path() const { return pty_.path(); }
    // Reads what the host wrote (readable: poll said so), runs the device up to now_utime,
    // writes its output. Returns bytes the host did not take (dropped, as on a full UART).
    virtual std::size_t service(bool readable, int64_t now_utime) = 0;
    // One line for the end-of-run report: what the device sent.
    virtual std::string summary() const = 0;

protected:
    std::size_t read_input(std::vector<uint8_t>& into);
    std::size_t write_output(const uint8_t* data, std::size_t n);
    io::Pty pty_;
};

// The servo's tilt as the drive's encoder had it, kept for the laser's beams (which are
// measured up to ~45 ms before their scan is sent).
class TiltHistory
{
public:
    void add(int64_t utime, double tilt_rad);
    double at(int64_t utime) const;  // linear between samples, clamped at the ends

private:
    std::deque<std::pair<int64_t, double>> samples_;
};

class ServoPort : public DevicePort
{
public:
    ServoPort(const std::string& link_path, const simworld::ServoSpec& spec, int64_t now_utime, TiltHistory& tilt);
    std::size_t service(bool readable, int64_t now_utime) override;
    double tilt_rad() const;
    std::string summary() const override;

private:
    servo::DriveEmulator drive_;
    servo::SlcanAdapter adapter_;
    double counts_per_rad_;
    TiltHistory& tilt_;
    std::string name_;  // "servo" or "servo-NAME", for the summary
    int64_t last_step_utime_ = 0;
    uint64_t frames_sent_ = 0;
};

class LmsPort : public DevicePort
{
public:
    // The LMS of world.scenario().lasers[laser], on the tilt its servo recorded. timing: the
    // emulator's beam timing options (linear_timing, sweep orders); the rest of the device
    // options come from the world.
    LmsPort(const std::string& link_path, const simworld::World& world, std::size_t laser, const TiltHistory& tilt,
            uint32_t seed, const lms::DeviceOptions& timing);
    std::size_t service(bool readable, int64_t now_utime) override;
    const lms::DeviceStats& stats() const { return device_->stats(); }
    std::string summary() const override;

private:
    std::unique_ptr<lms::LmsDevice> device_;
    std::mt19937 rng_;
    std::string name_;  // "lms" or "lms-NAME", for the summary
};

class GpsPort : public DevicePort
{
public:
    GpsPort(const std::string& link_path, const simworld::World& world, int64_t now_utime, uint32_t seed);
    std::size_t service(bool readable, int64_t now_utime) override;
    std::string summary() const override;

private:
    std::unique_ptr<gps::GpsEmulator> receiver_;
    uint64_t bytes_sent_ = 0;
};

class ImuPort : public DevicePort
{
public:
    static constexpr int kBaud = 38400;
    ImuPort(const std::string& link_path, const simworld::World& world, int64_t now_utime, uint32_t seed);
    std::size_t service(bool readable, int64_t now_utime) override;
    std::string summary() const override;

private:
    std::unique_ptr<imu::Gx1Emulator> unit_;
};

}  // namespace ugv::sim::world
