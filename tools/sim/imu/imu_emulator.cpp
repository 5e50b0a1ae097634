#include "imu_emulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "ugv/microstrain_gx1/orientation.hpp"
#include "ugv/microstrain_gx1/protocol.hpp"
#include "ugv/sim/line_faults.hpp"

namespace ugv::sim::imu {

namespace gx1 = ugv::microstrain_gx1;
namespace cmd = gx1::cmd;

AttitudeFn fixed_attitude(double roll_rad, double pitch_rad, double yaw_rad)
{
    return [=](double) {
        NedMotion m;
        m.roll_rad = roll_rad;
        m.pitch_rad = pitch_rad;
        m.yaw_rad = yaw_rad;
        return m;
    };
}

AttitudeFn slow_yaw(double yaw0_rad, double yaw_rate_radps)
{
    return [=](double t_s) {
        NedMotion m;
        m.yaw_rad = std::remainder(yaw0_rad + yaw_rate_radps * t_s, 2.0 * 3.14159265358979323846);
        m.rate_frd_radps = {0, 0, yaw_rate_radps};  // level: NED down = sensor down
        return m;
    };
}

AttitudeFn bench_motions(double t0_s, double yaw0_rad)
{
    constexpr double kDeg = 3.14159265358979323846 / 180.0;
    struct Segment
    {
        double seconds;
        int axis;  // 0 roll, 1 pitch, 2 yaw; -1 level
        double from_deg, to_deg;
    };
    // No hold at a displaced attitude: the only still moments are level at yaw0, where the
    // bench arms, so the first motion after each is the one it asks for.
    static const Segment kCycle[] = {
        {3, -1, 0, 0}, {1, 0, 0, 30},  {1, 0, 30, 0},  {3, -1, 0, 0}, {1, 1, 0, 20}, {1, 1, 20, 0},
        {3, -1, 0, 0}, {2, 2, 0, -90}, {2, 2, -90, 0}, {3, -1, 0, 0},
    };
    double cycle_s = 0;
    for (const auto& s : kCycle) cycle_s += s.seconds;
    return [=](double t_s) {
        double t = std::fmod(std::max(0.0, t_s - t0_s), cycle_s);
        NedMotion m;
        m.yaw_rad = yaw0_rad;
        for (const auto& s : kCycle) {
            if (t >= s.seconds) {
                t -= s.seconds;
                continue;
            }
            if (s.axis < 0) break;
            const double angle = (s.from_deg + (s.to_deg - s.from_deg) * t / s.seconds) * kDeg;
            const double rate = (s.to_deg - s.from_deg) / s.seconds * kDeg;
            if (s.axis == 0) m.roll_rad = angle;
            if (s.axis == 1) m.pitch_rad = angle;
            if (s.axis == 2) m.yaw_rad = std::remainder(yaw0_rad + angle, 2.0 * 3.14159265358979323846);
            m.rate_frd_radps[s.axis] = rate;
            break;
        }
        return m;
    };
}

std::size_t random_chunk_size(std::mt19937& rng, std::size_t available)
{
    if (available <= 1) return available;
    // Half of the writes cut anywhere; the rest go out whole, as a USB-serial bridge does.
    if (std::uniform_int_distribution<int>(0, 1)(rng) == 0)
        return std::uniform_int_distribution<std::size_t>(1, available)(rng);
    return available;
}

namespace {

// Argument bytes that follow each host command.
std::size_t argument_bytes(uint8_t command)
{
    switch (command) {
    case cmd::continuous:
    case cmd::read_eeprom: return 2;
    case cmd::tare:
    case cmd::remove_tare: return 3;
    case cmd::write_gains:
    case cmd::write_eeprom: return 6;
    default: return 0;
    }
}

bool is_data_command(uint8_t c)
{
    switch (c) {
    case cmd::raw_sensor:
    case cmd::stab_vectors:
    case cmd::inst_vectors:
    case cmd::inst_quaternion:
    case cmd::stab_quaternion:
    case cmd::inst_matrix:
    case cmd::stab_matrix:
    case cmd::stab_quaternion_vectors:
    case cmd::inst_euler:
    case cmd::stab_euler:
    case cmd::stab_euler_accel_rate: return true;
    default: return false;
    }
}

uint16_t u(int16_t v) { return static_cast<uint16_t>(v); }

}  // namespace

Gx1Emulator::Gx1Emulator(EmulatorConfig config, double power_on_s)
    : config_(std::move(config)), power_on_s_(power_on_s), rng_(config_.noise.seed)
{
    if (config_.ahrs) {
        AhrsConfig a = *config_.ahrs;
        a.mag_field_ned_gauss = config_.mag_field_ned_gauss;
        ahrs_ = std::make_unique<AhrsModel>(a, config_.ahrs_start_s >= 0 ? config_.ahrs_start_s : power_on_s,
                                            config_.attitude);
    }
    eeprom_[gx1::eeprom::gyro_gain_scale] = config_.gyro_gain_scale;
    eeprom_[gx1::eeprom::accel_gain_scale] = config_.accel_gain_scale;
    eeprom_[gx1::eeprom::mag_gain_scale] = config_.mag_gain_scale;
    for (std::size_t i = 0; i < 4; ++i) eeprom_[gx1::eeprom::timing[i]] = config_.timing.words[i];
    if (config_.streaming_at_power_on) start_stream(config_.power_on_command, power_on_s);
}

uint16_t Gx1Emulator::eeprom(uint16_t address) const
{
    const auto it = eeprom_.find(address);
    return it == eeprom_.end() ? 0xFFFF : it->second;  // erased cells read all ones
}

double Gx1Emulator::tick_period_s() const
{
    gx1::TimingWords t;
    for (std::size_t i = 0; i < 4; ++i) t.words[i] = eeprom(gx1::eeprom::timing[i]);
    const double tick = t.tick_period_s();
    return tick > 0 ? tick : gx1::TimingWords{}.tick_period_s();
}

int64_t Gx1Emulator::device_ticks_at(double t_s) const
{
    const double device_s = (t_s - power_on_s_) * (1.0 + config_.clock_ppm * 1e-6);
    return static_cast<int64_t>(std::floor(device_s / tick_period_s() + 1e-9)) + config_.timer_at_power_on;
}

double Gx1Emulator::host_time_of_tick(int64_t tick) const
{
    return power_on_s_ +
           static_cast<double>(tick - config_.timer_at_power_on) * tick_period_s() / (1.0 + config_.clock_ppm * 1e-6);
}

uint16_t Gx1Emulator::ticks_at(double t_s) const { return static_cast<uint16_t>(device_ticks_at(t_s) & 0xFFFF); }

double Gx1Emulator::next_frame_s() const
{
    return streaming_ ? host_time_of_tick(next_tick_) : std::numeric_limits<double>::infinity();
}

void Gx1Emulator::send(const std::vector<uint8_t>& bytes)
{
    if (!silent_) out_.insert(out_.end(), bytes.begin(), bytes.end());
}

void Gx1Emulator::send_reply(std::vector<uint8_t> bytes)
{
    if (truncate_replies_ > 0 && bytes.size() > 1) {
        --truncate_replies_;
        bytes.resize(sim::cut_length(bytes.size(), rng_));
        ++counters_.replies_truncated;
    }
    send(bytes);
}

void Gx1Emulator::inject_garbage(std::size_t n)
{
    static constexpr uint8_t likely[] = {cmd::stab_euler_accel_rate, cmd::continuous, cmd::stab_quaternion_vectors,
                                         0x00, 0xFF};
    std::uniform_int_distribution<int> byte(0, 255), pick(0, 4), coin(0, 2);
    for (std::size_t i = 0; i < n; ++i)
        out_.push_back(coin(rng_) == 0 ? likely[pick(rng_)] : static_cast<uint8_t>(byte(rng_)));
}

void Gx1Emulator::start_stream(uint8_t command, double t_s)
{
    streaming_ = true;
    stream_command_ = command;
    period_ticks_ = std::max<int64_t>(1, std::llround(1.0 / (config_.rate_hz * tick_period_s())));
    next_tick_ = device_ticks_at(t_s) + period_ticks_;
}

void Gx1Emulator::advance(double t_s)
{
    while (streaming_ && host_time_of_tick(next_tick_) <= t_s) {
        const double sample_s = host_time_of_tick(next_tick_);
        auto frame = build_data_reply(stream_command_, sample_s, static_cast<uint16_t>(next_tick_ & 0xFFFF));
        if (!silent_) {
            ++counters_.frames_streamed;
            if (truncate_every_ > 0 && counters_.frames_streamed % truncate_every_ == 0 && frame.size() > 1) {
                frame.resize(sim::cut_length(frame.size(), rng_));
                ++counters_.frames_truncated;
            }
        }
        send(frame);
        next_tick_ += period_ticks_;
    }
}

void Gx1Emulator::receive(const uint8_t* data, std::size_t n, double t_s)
{
    if (silent_) return;
    advance(t_s);  // frames due before the command go out first
    for (std::size_t i = 0; i < n; ++i) {
        const uint8_t b = data[i];
        if (pending_.empty() && !gx1::is_command(b)) {
            ++counters_.ignored_bytes;
            continue;
        }
        pending_.push_back(b);
        if (pending_.size() == 1 + argument_bytes(pending_[0])) {
            execute(pending_, t_s);
            pending_.clear();
        }
    }
}

std::vector<uint8_t> Gx1Emulator::data_reply(uint8_t command, double t_s)
{
    return build_data_reply(command, t_s, ticks_at(t_s));
}

std::vector<uint8_t> Gx1Emulator::build_data_reply(uint8_t command, double t_s, uint16_t ticks)
{
    const NoiseModel& nm = config_.noise;
    NedMotion m = config_.attitude(t_s);
    // The sensors measure the true attitude; the attitude output is the filter's (or the
    // truth), with white noise on top.
    const Eigen::Matrix3d r_true = gx1::rotation_from_euler(m.roll_rad, m.pitch_rad, m.yaw_rad);
    Eigen::Matrix3d r_out = r_true;
    Eigen::Vector3d b_gauss = r_true.transpose() * config_.mag_field_ned_gauss;
    if (ahrs_) {
        m.rate_frd_radps += ahrs_->advance(t_s).gyro_bias_radps;
        r_out = ahrs_->attitude(m);
        b_gauss = ahrs_->measured_field(m);
    }
    Eigen::Vector3d rpy = gx1::euler_from_rotation(r_out);
    m.roll_rad = rpy.x() + noise(nm.angle_sigma_rad);
    m.pitch_rad = rpy.y() + noise(nm.angle_sigma_rad);
    m.yaw_rad = std::remainder(rpy.z() + noise(nm.angle_sigma_rad), 2.0 * 3.14159265358979323846);
    const Eigen::Matrix3d r_ned_frd = gx1::rotation_from_euler(m.roll_rad, m.pitch_rad, m.yaw_rad);
    const double gyro = eeprom(gx1::eeprom::gyro_gain_scale), accel = eeprom(gx1::eeprom::accel_gain_scale),
                 mag = eeprom(gx1::eeprom::mag_gain_scale);
    // Specific force: the acceleration minus gravity (the reaction to gravity is "up" =
    // -down in NED), in sensor axes, in g.
    const Eigen::Vector3d f_g =
        r_true.transpose() * (m.accel_ned_mps2 / gx1::standard_gravity_mps2 - Eigen::Vector3d(0, 0, 1.0));

    std::vector<uint16_t> words;
    auto push_vectors = [&](bool with_mag) {
        if (with_mag)
            for (int i = 0; i < 3; ++i) words.push_back(u(gx1::vector_raw(b_gauss[i], mag)));
        for (int i = 0; i < 3; ++i)
            words.push_back(u(gx1::vector_raw(
                f_g[i] + noise(nm.accel_sigma_mps2) / gx1::standard_gravity_mps2, accel)));
        for (int i = 0; i < 3; ++i)
            words.push_back(u(gx1::vector_raw(m.rate_frd_radps[i] + noise(nm.rate_sigma_radps), gyro)));
    };
    auto push_quaternion = [&] {
        Eigen::Quaterniond q(r_ned_frd);
        if (q.w() < 0) q.coeffs() *= -1.0;
        for (double c : {q.w(), q.x(), q.y(), q.z()}) words.push_back(u(gx1::unit_raw(c)));
    };
    switch (command) {
    case cmd::raw_sensor:
        // A/D counts around mid-scale; no physical meaning is promised for raw bits.
        for (int i = 0; i < 3; ++i) words.push_back(static_cast<uint16_t>(32768 + std::lround(b_gauss[i] * 1000)));
        for (int i = 0; i < 3; ++i) words.push_back(static_cast<uint16_t>(32768 + std::lround(f_g[i] * 1000)));
        for (int i = 0; i < 3; ++i) words.push_back(static_cast<uint16_t>(32768 + std::lround(m.rate_frd_radps[i] * 1000)));
        break;
    case cmd::stab_vectors:
    case cmd::inst_vectors: push_vectors(true); break;
    case cmd::inst_quaternion:
    case cmd::stab_quaternion: push_quaternion(); break;
    case cmd::inst_matrix:
    case cmd::stab_matrix: {
        const Eigen::Matrix3d m_ned_to_sensor = r_ned_frd.transpose();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) words.push_back(u(gx1::unit_raw(m_ned_to_sensor(r, c))));
        break;
    }
    case cmd::stab_quaternion_vectors:
        push_quaternion();
        push_vectors(true);
        break;
    case cmd::inst_euler:
    case cmd::stab_euler:
    case cmd::stab_euler_accel_rate:
        words.push_back(u(gx1::euler_raw(m.roll_rad)));
        words.push_back(u(gx1::euler_raw(m.pitch_rad)));
        words.push_back(u(gx1::euler_raw(m.yaw_rad)));
        if (command == cmd::stab_euler_accel_rate) push_vectors(false);
        break;
    default: return {};
    }
    words.push_back(ticks);
    return gx1::encode_reply(command, words);
}

void Gx1Emulator::execute(const std::vector<uint8_t>& c, double t_s)
{
    const uint16_t ticks = ticks_at(t_s);
    const uint8_t command = c[0];
    auto arg16 = [&](std::size_t i) { return static_cast<uint16_t>(c[i] << 8 | c[i + 1]); };
    ++counters_.commands;
    if (is_data_command(command)) {
        send_reply(data_reply(command, t_s));
        return;
    }
    switch (command) {
    case cmd::continuous:
        if (c[2] == 0x00) {
            streaming_ = false;
        } else if (is_data_command(c[2])) {
            start_stream(c[2], t_s);
        } else {
            return;  // not a streamable command: no answer
        }
        send_reply(gx1::encode_reply(cmd::continuous, {static_cast<uint16_t>(c[1] << 8 | c[2]), ticks}));
        return;
    case cmd::tare:
    case cmd::remove_tare:
        // Acknowledged only with the confirmation bytes; the reference frame is not changed.
        if (c[1] == 0xC1 && c[2] == 0xC3 && c[3] == 0xC5) send_reply(gx1::encode_reply(command, {ticks}));
        return;
    case cmd::capture_gyro_bias: send_reply(gx1::encode_reply(command, {ticks})); return;
    case cmd::temperature: {
        const double raw = (config_.temperature_c / 100.0 + 0.5) * 65536.0 / 5.0;
        send_reply(gx1::encode_reply(command, {static_cast<uint16_t>(std::lround(raw)), ticks}));
        return;
    }
    case cmd::write_gains:
        system_gains_ = {arg16(1), arg16(3), arg16(5)};
        send_reply(gx1::encode_reply(command, {ticks}));
        return;
    case cmd::read_gains:
        send_reply(gx1::encode_reply(command, {system_gains_[0], system_gains_[1], system_gains_[2], ticks}));
        return;
    case cmd::read_eeprom: send_reply(gx1::encode_reply(command, {eeprom(arg16(1)), ticks})); return;
    case cmd::write_eeprom:
        if (c[1] != 0x71 || c[6] != 0xAA) return;  // wrong confirmation bytes: ignored
        eeprom_[arg16(2)] = arg16(4);
        send_reply(gx1::encode_reply(command, {arg16(4), ticks}));
        return;
    case cmd::firmware_version: send_reply(gx1::encode_reply(command, {config_.firmware_version})); return;
    case cmd::serial_number: send_reply(gx1::encode_reply(command, {config_.serial_number})); return;
    default: return;
    }
}

}  // namespace ugv::sim::imu
