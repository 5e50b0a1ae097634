#include "run_folder.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "ugv/io/whole_file.hpp"

namespace ugv::sim::world {

namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

std::string triple(const Eigen::Vector3d& v, double scale)
{
    std::ostringstream s;
    s.precision(10);
    s << '[' << v[0] * scale << ", " << v[1] * scale << ", " << v[2] * scale << ']';
    return s.str();
}

// The configured mounts are what the daemons are told; the true ones are the simulator's.
std::string kind(bool truth) { return truth ? " (true)" : " (as configured)"; }

}  // namespace

std::string nodscan_calibration(const simworld::Scenario& s, std::size_t laser, bool truth)
{
    const simworld::LaserSpec& l = s.lasers.at(laser);
    const nodscan::MountGeometry& m = truth ? l.mount : l.configured_mount;
    const std::string which = l.name.empty() ? "laser mount" : "mount of laser " + l.name;
    return "# The simulated vehicle's " + which + kind(truth) + " (ugv-sim world, scenario " + s.name + ")\n[mount]\n" +
           "tilt_axis_xyz_m = " + triple(m.axis_xyz_m, 1.0) + "\n" + "tilt_axis_rpy_deg = " +
           triple(m.axis_rpy_rad, kRadToDeg) + "\n" + "laser_xyz_m = " + triple(m.laser_xyz_m, 1.0) + "\n" +
           "laser_rpy_deg = " + triple(m.laser_rpy_rad, kRadToDeg) + "\n";
}

std::string servo_calibration(const simworld::Scenario& s, std::size_t laser)
{
    const simworld::LaserSpec& l = s.lasers.at(laser);
    std::ostringstream o;
    o.precision(12);
    o << "# The drive nodding laser " << l.name << " (ugv-sim world, scenario " << s.name << ")\n"
      << "node_id = " << l.servo.node_id << "\ncounts_per_rev = " << l.servo.counts_per_rev
      << "\ngear_ratio = " << l.servo.gear_ratio << "\n";
    return o.str();
}

std::string pose_calibration(const simworld::Scenario& s, bool truth)
{
    std::ostringstream o;
    o.precision(12);
    const Eigen::Vector3d& a = truth ? s.gps.antenna_m : s.gps.configured_antenna_m;
    o << "# The simulated vehicle's antenna" << kind(truth) << " and the scenario's datum (ugv-sim world, scenario "
      << s.name << ")\n"
      << "gps_antenna_m = [" << a.x() << ", " << a.y() << ", " << a.z() << "]\n"
      << "[datum]\nlat = " << s.datum_latitude_deg << "\nlon = " << s.datum_longitude_deg
      << "\nheight = " << s.datum_height_m << "\n";
    return o.str();
}

std::string imu_calibration(const simworld::Scenario& s, bool truth)
{
    return "# The simulated vehicle's IMU mounting" + kind(truth) + " (ugv-sim world, scenario " + s.name +
           ")\nmount_rpy_deg = " + triple(truth ? s.imu.mount_rpy_rad : s.imu.configured_mount_rpy_rad, kRadToDeg) +
           "\n";
}

void write_file(const std::string& path, const std::string& bytes)
{
    std::string why;
    if (!io::write_file_atomically(path, bytes.data(), bytes.size(), why)) throw std::runtime_error(why);
}

void write_run_folder(const std::string& dir, const simworld::World& world, const std::string& scenario_toml)
{
    for (const char* sub : {"/calibration", "/true-calibration"})
        if (::mkdir((dir + sub).c_str(), 0755) != 0 && errno != EEXIST)
            throw std::runtime_error(dir + sub + ": " + std::strerror(errno));
    write_file(dir + "/truth.hf", simworld::encode_height_field(world.field()));
    write_file(dir + "/scenario.toml", scenario_toml);
    const simworld::Scenario& s = world.scenario();
    for (std::size_t k = 0; k < s.lasers.size(); ++k) {
        write_file(dir + "/calibration/nodscan" + s.lasers[k].suffix() + ".toml", nodscan_calibration(s, k));
        write_file(dir + "/true-calibration/nodscan" + s.lasers[k].suffix() + ".toml", nodscan_calibration(s, k, true));
        // A named laser's drive may have any node id; the one laser of a scenario without
        // [[laser]] keeps ugv-servo's defaults, as it always has.
        if (!s.lasers[k].name.empty())
            write_file(dir + "/calibration/servo" + s.lasers[k].suffix() + ".toml", servo_calibration(s, k));
    }
    write_file(dir + "/calibration/pose.toml", pose_calibration(s));
    write_file(dir + "/calibration/imu.toml", imu_calibration(s));
    write_file(dir + "/true-calibration/pose.toml", pose_calibration(s, true));
    write_file(dir + "/true-calibration/imu.toml", imu_calibration(s, true));
}

}  // namespace ugv::sim::world
