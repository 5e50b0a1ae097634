#include "device_ports.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>

#include "ugv/geometry/rotation.hpp"
#include "ugv/microstrain_gx1/orientation.hpp"

namespace ugv::sim::world {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;

}  // namespace

std::size_t DevicePort::read_input(std::vector<uint8_t>& into)
{
    into.resize(4096);
    const ssize_t n = ::read(pty_.master_fd(), into.data(), into.size());
    into.resize(n > 0 ? static_cast<std::size_t>(n) : 0);
    return into.size();
}

std::size_t DevicePort::write_output(const uint8_t* data, std::size_t n)
{
    std::size_t done = 0;
    while (done < n) {
        const ssize_t w = ::write(pty_.master_fd(), data + done, n - done);
        if (w > 0) {
            done += static_cast<std::size_t>(w);
        } else if (w < 0 && errno == EINTR) {
            continue;
        } else {
            break;  // nobody reads: a real line would lose these bytes too
        }
    }
    return n - done;
}

void TiltHistory::add(int64_t utime, double tilt_rad)
{
    samples_.emplace_back(utime, tilt_rad);
    while (samples_.size() > 2 && samples_.front().first < utime - 500'000) samples_.pop_front();
}

double TiltHistory::at(int64_t utime) const
{
    if (samples_.empty()) return 0.0;
    if (utime <= samples_.front().first) return samples_.front().second;
    if (utime >= samples_.back().first) return samples_.back().second;
    const auto hi = std::lower_bound(samples_.begin(), samples_.end(), utime,
                                     [](const auto& s, int64_t t) { return s.first < t; });
    const auto lo = hi - 1;
    const double f = static_cast<double>(utime - lo->first) / static_cast<double>(hi->first - lo->first);
    return lo->second + f * (hi->second - lo->second);
}

namespace {

std::string base_name(const std::string& path)
{
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

ServoPort::ServoPort(const std::string& link_path, const simworld::ServoSpec& spec, int64_t now_utime, TiltHistory& tilt)
    : DevicePort(link_path),
      drive_([&] {
          servo::DriveModel m;
          m.node_id = static_cast<uint8_t>(spec.node_id);
          return m;
      }()),
      counts_per_rad_(spec.counts_per_rad()),
      tilt_(tilt),
      name_(base_name(link_path))
{
    drive_.power_on(now_utime);
    tilt_.add(now_utime, tilt_rad());
    last_step_utime_ = now_utime;
}

double ServoPort::tilt_rad() const
{
    return drive_.position_counts() / counts_per_rad_;
}

std::size_t ServoPort::service(bool readable, int64_t now)
{
    // The axis's path millisecond by millisecond, so that the laser's beams see the tilt the
    // drive had at their time even across a stall of this process (the drive catches up in
    // 1 ms steps; one sample at the end would draw a straight line through a turn-around).
    for (int64_t t = last_step_utime_ + 1000; t <= now; t += 1000) {
        drive_.advance(t);
        tilt_.add(t, tilt_rad());
        last_step_utime_ = t;
    }
    std::vector<uint8_t> in;
    if (readable && read_input(in) > 0)
        for (const auto& f : adapter_.feed(in.data(), in.size(), now)) drive_.on_frame(f, now);
    drive_.advance(now);
    tilt_.add(now, tilt_rad());
    for (const auto& f : drive_.take_outgoing()) {
        adapter_.on_bus_frame(f, now);
        ++frames_sent_;
    }
    const std::string out = adapter_.take_output();
    return write_output(reinterpret_cast<const uint8_t*>(out.data()), out.size());
}

std::string ServoPort::summary() const
{
    return name_ + ": " + std::to_string(frames_sent_) + " CAN frames from the drive";
}

LmsPort::LmsPort(const std::string& link_path, const simworld::World& world, std::size_t laser,
                 const TiltHistory& tilt, uint32_t seed, const lms::DeviceOptions& timing)
    : DevicePort(link_path), rng_(seed), name_(base_name(link_path))
{
    lms::DeviceOptions o;
    o.linear_timing = timing.linear_timing;
    o.sweep_order_05 = timing.sweep_order_05;
    o.sweep_order_025 = timing.sweep_order_025;
    o.seed = seed;
    const double noise_m = world.scenario().lasers.at(laser).range_noise_m;
    o.beam_scene = [&world, &tilt, noise_m, laser, this](double angle_rad, int64_t beam_utime) {
        const simworld::TruthState s = world.truth(beam_utime);
        const double r = world.beam_range_m(s, tilt.at(beam_utime), angle_rad, 81.0, laser);
        if (!std::isfinite(r) || noise_m <= 0) return r;
        std::normal_distribution<double> noise(0.0, noise_m);
        return std::max(0.0, r + noise(rng_));
    };
    device_ = std::make_unique<lms::LmsDevice>(std::move(o));
}

std::size_t LmsPort::service(bool readable, int64_t now)
{
    std::vector<uint8_t> in, out;
    const int host_baud = pty_.slave_baud();
    if (readable && read_input(in) > 0) device_->receive(in.data(), in.size(), host_baud, now, out);
    device_->tick(now, host_baud, out);
    return write_output(out.data(), out.size());
}

std::string LmsPort::summary() const
{
    const lms::DeviceStats& s = device_->stats();
    return name_ + ": " + std::to_string(s.scans_sent) + " scans sent, " + std::to_string(s.scans_skipped) +
           " skipped (due while the line was busy or the simulator was late)";
}

GpsPort::GpsPort(const std::string& link_path, const simworld::World& world, int64_t now_utime, uint32_t seed)
    : DevicePort(link_path)
{
    const simworld::Scenario& s = world.scenario();
    gps::EmulatorConfig c;
    c.protocol = s.gps.protocol == "nmea" ? gps::Protocol::nmea : gps::Protocol::novatel;
    c.noise_scale = s.gps.noise_scale;
    c.seed = seed;
    if (s.gps.error_model == "markov") {
        gps::PositionErrorConfig m;
        const simworld::GpsClassError* classes[] = {&s.gps.rtk_fixed, &s.gps.rtk_float, &s.gps.dgps, &s.gps.sbas,
                                                    &s.gps.single};
        for (std::size_t i = 0; i < 5; ++i) m.classes[i] = {classes[i]->sigma_m, classes[i]->time_constant_s};
        m.classes[static_cast<std::size_t>(gps::FixClass::other)].time_constant_s = s.gps.single.time_constant_s;
        m.seed = seed ^ 0x6a5du;  // its own stream: line faults and other draws do not shift it
        c.markov = m;
    }
    c.script = gps::parse_script(s.gps.position_types);
    c.undulation_m = s.undulation_m;
    c.trajectory = [&world, undulation = s.undulation_m](int64_t utime) {
        const simworld::TruthState t = world.truth(utime);
        const simworld::Geodetic g = world.antenna_position(t);
        gps::AntennaTruth a;
        a.latitude_deg = g.latitude_deg;
        a.longitude_deg = g.longitude_deg;
        a.height_msl_m = g.height_m - undulation;
        const Eigen::Vector3d v = world.antenna_velocity(t);
        a.horizontal_speed_mps = std::hypot(v.x(), v.y());
        // Track over ground; standing still, a receiver reports the last one: the heading.
        const double yaw = a.horizontal_speed_mps > 0.01 ? std::atan2(v.y(), v.x()) : t.yaw_rad;
        double track = geometry::track_from_enu_yaw(yaw) * kRadToDeg;
        if (track < 0) track += 360.0;
        a.track_deg = track;
        a.vertical_speed_mps = v.z();
        return a;
    };
    receiver_ = std::make_unique<gps::GpsEmulator>(std::move(c), now_utime);
}

std::size_t GpsPort::service(bool readable, int64_t now)
{
    std::vector<uint8_t> in;
    // A host at another rate hears noise and is heard as noise: it gets nothing here.
    const bool baud_matches = pty_.slave_baud() == receiver_->baud();
    std::string out;
    if (readable && read_input(in) > 0 && baud_matches) out = receiver_->on_host_bytes(in.data(), in.size());
    out += receiver_->tick(now);
    bytes_sent_ += out.size();
    if (!baud_matches) return out.size();
    return write_output(reinterpret_cast<const uint8_t*>(out.data()), out.size());
}

std::string GpsPort::summary() const
{
    return "gps: " + std::to_string(bytes_sent_) + " bytes sent";
}

ImuPort::ImuPort(const std::string& link_path, const simworld::World& world, int64_t now_utime, uint32_t seed)
    : DevicePort(link_path)
{
    const simworld::ImuSpec& spec = world.scenario().imu;
    imu::EmulatorConfig c;
    constexpr double deg = kPi / 180.0;
    c.noise.angle_sigma_rad = spec.angle_sigma_deg * deg;
    c.noise.rate_sigma_radps = spec.rate_sigma_dps * deg;
    c.noise.accel_sigma_mps2 = spec.accel_sigma_mps2;
    c.noise.seed = seed;
    if (spec.error_model == "ahrs") {
        imu::AhrsConfig a;
        a.time_constant_s = spec.tilt_time_constant_s;
        a.gyro_bias_walk_radps_per_sqrt_s = spec.gyro_bias_walk_dps_per_sqrt_s * deg;
        a.mag_disturbance_rad = spec.mag_disturbance_deg * deg;
        a.seed = seed ^ 0x5eedu;  // its own stream: the white noise draws do not shift it
        c.ahrs = a;
        // The filter's steps on the scenario's clock, so one seed gives one error history.
        c.ahrs_start_s = static_cast<double>(world.start_utime()) * 1e-6;
    }
    // The unit's NED/FRD convention from the body's ENU/FLU truth and the unit's true mounting
    // (at the reference point): R_ned_frd = N R_enu_body R_body_sensor F, with N the ENU/NED
    // swap and F = diag(1, -1, -1); yaw plus the declination. Aligned: roll the same, pitch and
    // yaw rate negated, yaw clockwise from north.
    const Eigen::Matrix3d mount = microstrain_gx1::rotation_from_euler(spec.mount_rpy_rad.x(), spec.mount_rpy_rad.y(),
                                                                       spec.mount_rpy_rad.z());
    c.attitude = [&world, mount, declination = spec.declination_deg * deg](double t_s) {
        const simworld::TruthState s = world.truth(std::llround(t_s * 1e6));
        Eigen::Matrix3d swap;
        swap << 0, 1, 0, 1, 0, 0, 0, 0, -1;
        const Eigen::Matrix3d frd = Eigen::Vector3d(1, -1, -1).asDiagonal();
        const Eigen::Vector3d euler = microstrain_gx1::euler_from_rotation(swap * s.orientation.toRotationMatrix() * mount * frd);
        imu::NedMotion m;
        m.roll_rad = euler.x();
        m.pitch_rad = euler.y();
        m.yaw_rad = std::remainder(euler.z() + declination, 2 * kPi);
        m.rate_frd_radps = frd * (mount.transpose() * s.rate_body_radps);
        m.accel_ned_mps2 = swap * s.accel_mps2;
        return m;
    };
    unit_ = std::make_unique<imu::Gx1Emulator>(std::move(c), static_cast<double>(now_utime) * 1e-6);
}

std::size_t ImuPort::service(bool readable, int64_t now)
{
    std::vector<uint8_t> in;
    const double t_s = static_cast<double>(now) * 1e-6;
    const bool baud_matches = pty_.slave_baud() == kBaud;
    if (readable && read_input(in) > 0 && baud_matches) unit_->receive(in.data(), in.size(), t_s);
    unit_->advance(t_s);
    auto& q = unit_->output();
    if (q.empty()) return 0;
    std::vector<uint8_t> out(q.begin(), q.end());
    q.clear();
    if (!baud_matches) return out.size();
    return write_output(out.data(), out.size());
}

std::string ImuPort::summary() const
{
    return "imu: " + std::to_string(unit_->counters().frames_streamed) + " frames streamed";
}

}  // namespace ugv::sim::world
