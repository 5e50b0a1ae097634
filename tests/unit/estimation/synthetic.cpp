#include "synthetic.hpp"

#include <cmath>
#include <numbers>
#include <optional>

#include "ugv/geometry/rotation.hpp"

namespace ugv::estimation::synthetic {

using Eigen::Vector3d;

namespace {

constexpr double kGravity = 9.80665;

Truth from_motion(const Vector3d& p, const Vector3d& v, const Vector3d& a, double yaw_at_rest)
{
    Truth t{p, v, a, yaw_at_rest, 0.0};
    const double s2 = v.head<2>().squaredNorm();
    if (s2 > 1e-12) {
        t.yaw = std::atan2(v.y(), v.x());
        t.yaw_rate = (v.x() * a.y() - v.y() * a.x()) / s2;
    }
    return t;
}

}  // namespace

Eigen::Quaterniond Truth::attitude() const
{
    return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Vector3d::UnitZ()));
}

Trajectory straight(double heading_rad, double accel_mps2, double speed_mps)
{
    return [=](double t) {
        const Vector3d dir(std::cos(heading_rad), std::sin(heading_rad), 0.0);
        const double t_acc = speed_mps / accel_mps2;
        double s, v, a;
        if (t < t_acc) {
            s = 0.5 * accel_mps2 * t * t;
            v = accel_mps2 * t;
            a = accel_mps2;
        } else {
            s = 0.5 * accel_mps2 * t_acc * t_acc + speed_mps * (t - t_acc);
            v = speed_mps;
            a = 0.0;
        }
        return from_motion(s * dir, v * dir, a * dir, heading_rad);
    };
}

Trajectory circle(double radius_m, double speed_mps)
{
    return [=](double t) {
        const double w = speed_mps / radius_m;
        const double c = std::cos(w * t), s = std::sin(w * t);
        return from_motion(Vector3d(radius_m * c, radius_m * s, 0.0), Vector3d(-speed_mps * s, speed_mps * c, 0.0),
                           Vector3d(-speed_mps * w * c, -speed_mps * w * s, 0.0), 0.0);
    };
}

Trajectory figure_eight(double a_m, double w)
{
    return [=](double t) {
        const Vector3d p(a_m * std::sin(w * t), 0.5 * a_m * std::sin(2 * w * t), 0.0);
        const Vector3d v(a_m * w * std::cos(w * t), a_m * w * std::cos(2 * w * t), 0.0);
        const Vector3d acc(-a_m * w * w * std::sin(w * t), -2.0 * a_m * w * w * std::sin(2 * w * t), 0.0);
        return from_motion(p, v, acc, 0.0);
    };
}

int64_t utime_of(const Input& in)
{
    return std::visit([](const auto& x) { return x.utime; }, in);
}

Run simulate(const Trajectory& trajectory, const Noise& noise, const Datum& datum, double duration_s, uint32_t seed,
             int64_t start_utime)
{
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> n01(0.0, 1.0);
    const auto gauss3 = [&](double sigma) -> Vector3d { return Vector3d(n01(rng), n01(rng), n01(rng)) * sigma; };
    const LocalFrame frame(datum);
    Run run;
    run.start_utime = start_utime;

    const auto imu_period = static_cast<int64_t>(std::llround(1e6 / noise.imu_hz));
    const auto gps_period = static_cast<int64_t>(std::llround(1e6 / noise.gps_hz));
    const auto end = static_cast<int64_t>(duration_s * 1e6);
    // Merge the two sensor clocks; the GPS clock is offset by 3 ms so stamps rarely tie.
    int64_t next_imu = 0, next_gps = 3'000;
    const double imu_dt = static_cast<double>(imu_period) * 1e-6;
    std::optional<Eigen::Quaterniond> ahrs;  // the AHRS's attitude (true yaw, its own tilt)
    while (next_imu <= end || next_gps <= end) {
        if (next_imu <= next_gps) {
            const double t = static_cast<double>(next_imu) * 1e-6;
            const Truth tr = trajectory(t);
            ImuSample s;
            s.utime = start_utime + next_imu;
            s.has_orientation = s.has_rate = s.has_accel = true;
            const Eigen::Quaterniond q = tr.attitude();
            s.rate_rps = Vector3d(0.0, 0.0, tr.yaw_rate) + noise.gyro_bias_rps +
                         gauss3(noise.gyro_density * std::sqrt(noise.imu_hz));
            s.accel_mps2 = q.conjugate() * (tr.acceleration + Vector3d(0.0, 0.0, kGravity)) +
                           gauss3(noise.accel_density * std::sqrt(noise.imu_hz));
            Eigen::Quaterniond attitude = q;
            if (noise.ahrs_time_constant_s > 0.0) {
                if (!ahrs) {
                    ahrs = q;
                } else {
                    // Integrate the gyros, then pull the accelerometers' "up" toward Up.
                    Eigen::Quaterniond a = (*ahrs * geometry::quaternion_exp(s.rate_rps * imu_dt)).normalized();
                    const Vector3d up_seen = (a * s.accel_mps2).normalized();
                    const Vector3d pull = up_seen.cross(Vector3d::UnitZ()) * (imu_dt / noise.ahrs_time_constant_s);
                    a = (geometry::quaternion_exp(pull) * a).normalized();
                    geometry::Euler e = geometry::euler_from_quaternion(a);
                    e.yaw = tr.yaw;
                    ahrs = geometry::quaternion_from_euler(e);
                }
                attitude = *ahrs;
            }
            const double compass_error = noise.heading_offset_rad + noise.compass_deviation_rad * std::sin(tr.yaw);
            const Eigen::Quaterniond magnetic =
                Eigen::Quaterniond(Eigen::AngleAxisd(compass_error, Vector3d::UnitZ())) * attitude;
            s.orientation = (geometry::quaternion_exp(gauss3(noise.imu_orientation_sigma_rad)) * magnetic).normalized();
            s.orientation_sigma_rad = noise.imu_orientation_sigma_rad;
            run.inputs.emplace_back(s);
            next_imu += imu_period;
        } else {
            const double t = static_cast<double>(next_gps) * 1e-6;
            const Truth tr = trajectory(t);
            const Vector3d enu = tr.position + Vector3d(n01(rng) * noise.gps_sigma_horizontal_m,
                                                        n01(rng) * noise.gps_sigma_horizontal_m,
                                                        n01(rng) * noise.gps_sigma_vertical_m);
            const Vector3d llh = frame.to_geodetic(enu);
            GpsFix f;
            f.utime = start_utime + next_gps;
            f.latitude_deg = llh.x();
            f.longitude_deg = llh.y();
            f.height_m = llh.z();
            f.sigma_east_m = f.sigma_north_m = noise.gps_sigma_horizontal_m;
            f.sigma_up_m = noise.gps_sigma_vertical_m;
            f.quality = FixQuality::dgps;
            run.inputs.emplace_back(f);

            const Vector3d v = tr.velocity + gauss3(noise.gps_velocity_sigma_mps);
            GpsVelocity gv;
            gv.utime = f.utime;
            gv.horizontal_speed_mps = v.head<2>().norm();
            gv.track_rad = std::atan2(v.x(), v.y());  // clockwise from north
            gv.vertical_speed_mps = v.z();
            run.inputs.emplace_back(gv);
            next_gps += gps_period;
        }
    }
    return run;
}

Truth truth_at(const Trajectory& trajectory, const Run& run, int64_t utime)
{
    return trajectory(static_cast<double>(utime - run.start_utime) * 1e-6);
}

}  // namespace ugv::estimation::synthetic
