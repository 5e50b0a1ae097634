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

}  // namespace

std::string nodscan_calibration(const simworld::Scenario& s)
{
    const nodscan::MountGeometry& m = s.laser.mount;
    return "# The simulated vehicle's laser mount (ugv-sim world, scenario " + s.name + ")\n[mount]\n" +
           "tilt_axis_xyz_m = " + triple(m.axis_xyz_m, 1.0) + "\n" + "tilt_axis_rpy_deg = " +
           triple(m.axis_rpy_rad, kRadToDeg) + "\n" + "laser_xyz_m = " + triple(m.laser_xyz_m, 1.0) + "\n" +
           "laser_rpy_deg = " + triple(m.laser_rpy_rad, kRadToDeg) + "\n";
}

std::string pose_calibration(const simworld::Scenario& s)
{
    std::ostringstream o;
    o.precision(12);
    const Eigen::Vector3d& a = s.gps.antenna_m;
    o << "# The simulated vehicle's antenna and the scenario's datum (ugv-sim world, scenario " << s.name << ")\n"
      << "gps_antenna_m = [" << a.x() << ", " << a.y() << ", " << a.z() << "]\n"
      << "[datum]\nlat = " << s.datum_latitude_deg << "\nlon = " << s.datum_longitude_deg
      << "\nheight = " << s.datum_height_m << "\n";
    return o.str();
}

void write_file(const std::string& path, const std::string& bytes)
{
    std::string why;
    if (!io::write_file_atomically(path, bytes.data(), bytes.size(), why)) throw std::runtime_error(why);
}

void write_run_folder(const std::string& dir, const simworld::World& world, const std::string& scenario_toml)
{
    if (::mkdir((dir + "/calibration").c_str(), 0755) != 0 && errno != EEXIST)
        throw std::runtime_error(dir + "/calibration: " + std::strerror(errno));
    write_file(dir + "/truth.hf", simworld::encode_height_field(world.field()));
    write_file(dir + "/scenario.toml", scenario_toml);
    write_file(dir + "/calibration/nodscan.toml", nodscan_calibration(world.scenario()));
    write_file(dir + "/calibration/pose.toml", pose_calibration(world.scenario()));
}

}  // namespace ugv::sim::world
