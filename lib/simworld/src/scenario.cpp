#include "ugv/simworld/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

namespace ugv::simworld {

namespace {

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
constexpr double kHuge = 100000.0;  // m: a bound for coordinates that only catches typos

Rect read_rect(runtime::Config& c)
{
    Rect r;
    r.x0_m = c.get_double("x0", 0, -kHuge, kHuge);
    r.y0_m = c.get_double("y0", 0, -kHuge, kHuge);
    r.x1_m = c.get_double("x1", 1, -kHuge, kHuge);
    r.y1_m = c.get_double("y1", 1, -kHuge, kHuge);
    if (!(r.x1_m > r.x0_m)) c.fail("x1", "must be greater than x0");
    if (!(r.y1_m > r.y0_m)) c.fail("y1", "must be greater than y0");
    return r;
}

Eigen::Vector3d vec3(runtime::Config& c, const std::string& key, const Eigen::Vector3d& def, double bound)
{
    const std::vector<double> v = c.get_doubles(key, {def.x(), def.y(), def.z()}, 3, -bound, bound);
    return {v[0], v[1], v[2]};
}

Eigen::Vector3d mount_vec(runtime::Config& c, const std::string& key, const Eigen::Vector3d& def, double bound,
                          double scale)
{
    const std::vector<double> v = c.get_doubles(key, {def(0) / scale, def(1) / scale, def(2) / scale}, 3, -bound, bound);
    return {v[0] * scale, v[1] * scale, v[2] * scale};
}

void read_terrain(runtime::Config& root, Scenario& s)
{
    runtime::Config t = root.section("terrain");
    s.terrain.ground_z_m = t.get_double("ground_z_m", 0.0, -1000, 1000);
    s.terrain.roughness_m = t.get_double("roughness_m", 0.0, 0.0, 1.0);
    s.terrain.roughness_wavelength_m = t.get_double("roughness_wavelength_m", 2.0, 0.1, 100.0);
    s.terrain.seed = static_cast<uint32_t>(t.get_int("seed", 1, 0, 0xffffffffLL));
    s.field_resolution_m = t.get_double("resolution_m", 0.05, 0.01, 1.0);
    s.field_margin_m = t.get_double("margin_m", 30.0, 1.0, 500.0);
    for (runtime::Config& b : root.tables("box")) {
        s.terrain.boxes.push_back({read_rect(b), b.get_double("height_m", 0.5, 0.0, 100.0)});
        b.finish();
    }
    for (runtime::Config& w : root.tables("wall")) {
        const std::vector<double> from = w.get_doubles("from", {0, 0}, 2, -kHuge, kHuge);
        const std::vector<double> to = w.get_doubles("to", {1, 0}, 2, -kHuge, kHuge);
        s.terrain.walls.push_back({from[0], from[1], to[0], to[1], w.get_double("thickness_m", 0.3, 0.01, 10.0),
                                   w.get_double("height_m", 3.0, 0.0, 100.0)});
        w.finish();
    }
    for (runtime::Config& r : root.tables("ramp")) {
        RampSpec ramp{read_rect(r), r.get_double("rise_m", 0.5, -10.0, 10.0), Direction::east};
        const std::string dir = r.get_enum("rises_towards", "east", {"east", "west", "north", "south"});
        ramp.rises_towards = dir == "east" ? Direction::east
                             : dir == "west" ? Direction::west
                             : dir == "north" ? Direction::north
                                              : Direction::south;
        s.terrain.ramps.push_back(ramp);
        r.finish();
    }
    for (runtime::Config& d : root.tables("ditch")) {
        s.terrain.ditches.push_back({read_rect(d), d.get_double("depth_m", 0.3, 0.0, 100.0)});
        d.finish();
    }
}

void read_path(runtime::Config& root, Scenario& s)
{
    runtime::Config p = root.section("path");
    const std::vector<double> start = p.get_doubles("start", {0, 0}, 2, -kHuge, kHuge);
    s.path.x0_m = start[0];
    s.path.y0_m = start[1];
    s.path.yaw0_rad = p.get_double("start_yaw_deg", 0.0, -360, 360) * kDegToRad;
    s.path.accel_mps2 = p.get_double("accel_mps2", 1.0, 0.05, 10.0);
    s.hold_s = p.get_double("hold_s", 5.0, 0.0, 3600.0);
    for (runtime::Config& g : root.tables("segment")) {
        PathSegment seg;
        const std::string kind = g.get_enum("kind", "straight", {"straight", "arc", "stop"});
        if (kind == "stop") {
            seg.kind = PathSegment::Kind::stop;
            seg.duration_s = g.get_double("duration_s", 1.0, 0.0, 3600.0);
        } else {
            seg.speed_mps = g.get_double("speed_mps", 3.0, 0.01, 3.0);
            if (kind == "straight") {
                seg.kind = PathSegment::Kind::straight;
                seg.length_m = g.get_double("length_m", 10.0, 0.0, 100000.0);
            } else {
                seg.kind = PathSegment::Kind::arc;
                seg.radius_m = g.get_double("radius_m", 10.0, 1.0, 100000.0);
                seg.turn_rad = g.get_double("turn_deg", 90.0, -3600.0, 3600.0) * kDegToRad;
            }
        }
        s.path.segments.push_back(seg);
        g.finish();
    }
}

// The true mount (KEY), then what ugv-nodscan is told (configured_KEY, default: the true one).
void read_mount(runtime::Config& l, LaserSpec& laser)
{
    auto both = [&l](const std::string& key, Eigen::Vector3d& truth, Eigen::Vector3d& configured,
                     const Eigen::Vector3d& def, double bound, double scale) {
        truth = mount_vec(l, key, def, bound, scale);
        configured = mount_vec(l, "configured_" + key, truth, bound, scale);
    };
    nodscan::MountGeometry& m = laser.mount;
    nodscan::MountGeometry& c = laser.configured_mount;
    both("tilt_axis_xyz_m", m.axis_xyz_m, c.axis_xyz_m, {0.0, 0.0, 0.87}, 10, 1.0);
    both("tilt_axis_rpy_deg", m.axis_rpy_rad, c.axis_rpy_rad, {0, 0, 0}, 180, kDegToRad);
    both("laser_xyz_m", m.laser_xyz_m, c.laser_xyz_m, {0, 0, 0}, 2, 1.0);
    both("laser_rpy_deg", m.laser_rpy_rad, c.laser_rpy_rad, {0, 0, 0}, 180, kDegToRad);
    laser.range_noise_m = l.get_double("range_noise_m", 0.01, 0.0, 1.0);
}

void read_servo(runtime::Config&& sv, ServoSpec& servo)
{
    servo.node_id = static_cast<int>(sv.get_int("node_id", 1, 1, 127));
    servo.counts_per_rev = sv.get_double("counts_per_rev", 4096, 1, 1e9);
    servo.gear_ratio = sv.get_double("gear_ratio", 50, 0.001, 1e6);
}

// A laser's name becomes file names (lms-NAME), a systemd instance and a channel suffix.
bool valid_laser_name(const std::string& n)
{
    if (n.empty() || n.size() > 16) return false;
    return std::all_of(n.begin(), n.end(), [](char ch) { return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9'); });
}

// [laser] + [servo]: today's one laser. [[laser]] tables: one laser each, its servo in
// [laser.servo] (each laser is nodded by its own drive, on its own CAN adapter).
void read_lasers(runtime::Config& root, Scenario& s)
{
    if (!root.has_tables("laser")) {
        LaserSpec one;
        runtime::Config l = root.section("laser");
        read_mount(l, one);
        read_servo(root.section("servo"), one.servo);
        s.lasers = {one};
        return;
    }
    if (root.has("servo"))
        root.fail("servo", "with [[laser]] tables each laser has its own servo ([laser.servo] after its [[laser]])");
    std::vector<runtime::Config> tables = root.tables("laser");
    if (tables.size() > kMaxLasers)
        root.fail("laser", std::to_string(tables.size()) + " lasers; at most " + std::to_string(kMaxLasers));
    s.lasers.clear();
    for (runtime::Config& l : tables) {
        LaserSpec laser;
        laser.name = l.get_string("name", "");
        if (!valid_laser_name(laser.name))
            l.fail("name", laser.name.empty() ? "is required in a [[laser]] table (e.g. \"left\")"
                                              : "\"" + laser.name + "\" is not 1 to 16 lower-case letters and digits");
        for (const LaserSpec& other : s.lasers)
            if (other.name == laser.name) l.fail("name", "\"" + laser.name + "\" names two lasers");
        read_mount(l, laser);
        read_servo(l.section("servo"), laser.servo);
        l.finish();
        s.lasers.push_back(laser);
    }
}

// Keys that only one error model reads: a clear error rather than a value silently unused.
void only_with(const runtime::Config& c, bool model_chosen, std::initializer_list<std::string> keys,
               const char* model)
{
    if (model_chosen) return;
    for (const std::string& k : keys)
        if (c.has(k)) c.fail(k, std::string("only used with ") + model + " (remove it, or choose that model)");
}

void read_sensors(runtime::Config& root, Scenario& s)
{
    runtime::Config v = root.section("vehicle");
    s.vehicle.wheelbase_m = v.get_double("wheelbase_m", 2.5, 0.5, 10.0);
    s.vehicle.track_m = v.get_double("track_m", 1.6, 0.3, 5.0);

    read_lasers(root, s);

    runtime::Config g = root.section("gps");
    s.gps.protocol = g.get_enum("protocol", "novatel", {"novatel", "nmea"});
    s.gps.position_types = g.get_string("position_types", "NARROW_INT@0");
    s.gps.noise_scale = g.get_double("noise_scale", 1.0, 0.0, 100.0);
    s.gps.antenna_m = vec3(g, "antenna_m", {0.0, 0.0, 1.8}, 20);
    s.gps.configured_antenna_m = vec3(g, "configured_antenna_m", s.gps.antenna_m, 20);
    s.gps.error_model = g.get_enum("error_model", "markov", {"markov", "white"});
    const bool markov = s.gps.error_model == "markov";
    for (auto [name, cls] : {std::pair{"rtk_fixed", &s.gps.rtk_fixed}, std::pair{"rtk_float", &s.gps.rtk_float},
                             std::pair{"dgps", &s.gps.dgps}, std::pair{"sbas", &s.gps.sbas},
                             std::pair{"single", &s.gps.single}}) {
        const std::string sigma_key = std::string(name) + "_sigma_m", tau_key = std::string(name) + "_time_constant_s";
        only_with(g, markov, {sigma_key, tau_key}, "error_model = \"markov\"");
        cls->sigma_m = g.get_double(sigma_key, cls->sigma_m, 0.001, 100.0);
        cls->time_constant_s = g.get_double(tau_key, cls->time_constant_s, 0.1, 86400.0);
    }

    runtime::Config i = root.section("imu");
    s.imu.error_model = i.get_enum("error_model", "ahrs", {"ahrs", "white"});
    const bool ahrs = s.imu.error_model == "ahrs";
    only_with(i, ahrs, {"tilt_time_constant_s", "gyro_bias_walk_dps_per_sqrt_s", "mag_disturbance_deg"},
              "error_model = \"ahrs\"");
    s.imu.tilt_time_constant_s = i.get_double("tilt_time_constant_s", 10.0, 0.1, 1000.0);
    s.imu.gyro_bias_walk_dps_per_sqrt_s = i.get_double("gyro_bias_walk_dps_per_sqrt_s", 0.0005, 0.0, 1.0);
    s.imu.mag_disturbance_deg = i.get_double("mag_disturbance_deg", 1.0, 0.0, 45.0);
    s.imu.angle_sigma_deg = i.get_double("angle_sigma_deg", ahrs ? 0.047 : 0.7, 0.0, 30.0);
    s.imu.rate_sigma_dps = i.get_double("rate_sigma_dps", 0.1, 0.0, 100.0);
    s.imu.accel_sigma_mps2 = i.get_double("accel_sigma_mps2", 0.02, 0.0, 100.0);
    s.imu.declination_deg = i.get_double("declination_deg", 0.0, -180, 180);
    s.imu.mount_rpy_rad = mount_vec(i, "mount_rpy_deg", {0, 0, 0}, 180, kDegToRad);
    s.imu.configured_mount_rpy_rad = mount_vec(i, "configured_mount_rpy_deg", s.imu.mount_rpy_rad, 180, kDegToRad);

    runtime::Config d = root.section("devices");
    s.devices.lms = d.get_bool("lms", true);
    s.devices.servo = d.get_bool("servo", true);
    s.devices.gps = d.get_bool("gps", true);
    s.devices.imu = d.get_bool("imu", true);
}

}  // namespace

double ServoSpec::counts_per_rad() const
{
    return counts_per_rev * gear_ratio / (2.0 * 3.14159265358979323846);
}

Scenario parse_scenario(runtime::Config& cfg)
{
    Scenario s;
    s.name = cfg.get_string("name", "unnamed");
    runtime::Config datum = cfg.section("datum");
    s.datum_latitude_deg = datum.get_double("lat", s.datum_latitude_deg, -90, 90);
    s.datum_longitude_deg = datum.get_double("lon", s.datum_longitude_deg, -180, 180);
    s.datum_height_m = datum.get_double("height", s.datum_height_m, -1000, 10000);
    s.undulation_m = datum.get_double("undulation_m", s.undulation_m, -200, 200);
    read_terrain(cfg, s);
    read_path(cfg, s);
    read_sensors(cfg, s);
    cfg.finish();
    return s;
}

const char* default_scenario_toml()
{
    return R"(# The report's demonstration (figures 16-19): stand while the stack starts, drive east at
# 3 m/s past a box (right) and a building wall (right), turn left, stop facing a wall.
name = "report-demo"

[datum]
lat = 50.2706
lon = -110.7389
height = 750.0
undulation_m = -17.0

[terrain]
ground_z_m = 0.0
roughness_m = 0.02
roughness_wavelength_m = 1.5
seed = 7
resolution_m = 0.05
margin_m = 30.0

[[box]]        # the obstacle of figures 17 and 19, right of the path
x0 = 22.0
y0 = -3.5
x1 = 23.0
y1 = -2.5
height_m = 0.6

[[wall]]       # the building wall of figure 16, right of the path
from = [32.0, -7.0]
to = [56.0, -7.0]
thickness_m = 0.3
height_m = 3.0

[[wall]]       # the wall the vehicle stops in front of (figure 18)
from = [47.0, 31.0]
to = [63.0, 31.0]
thickness_m = 0.3
height_m = 3.0

[[ramp]]
x0 = 14.0
y0 = 3.0
x1 = 18.0
y1 = 6.0
rise_m = 0.4
rises_towards = "east"

[[ditch]]
x0 = 26.0
y0 = 2.5
x1 = 28.0
y1 = 5.0
depth_m = 0.3

[path]
start = [0.0, 0.0]
start_yaw_deg = 0.0      # east
accel_mps2 = 1.0
hold_s = 15.0            # standing in front of the wall (figure 18)

[[segment]]              # the stack starts, the laser handshakes, the GPS fixes
kind = "stop"
duration_s = 10.0

[[segment]]
kind = "straight"
length_m = 45.0
speed_mps = 3.0

[[segment]]              # left turn (figure 19)
kind = "arc"
radius_m = 10.0
turn_deg = 90.0
speed_mps = 2.0

[[segment]]
kind = "straight"
length_m = 10.0
speed_mps = 2.0

[[segment]]
kind = "stop"
duration_s = 3.0

[vehicle]
wheelbase_m = 2.5
track_m = 1.6

[laser]
tilt_axis_xyz_m = [0.0, 0.0, 0.87]
tilt_axis_rpy_deg = [0.0, 0.0, 0.0]
laser_xyz_m = [0.0, 0.0, 0.0]
laser_rpy_deg = [0.0, 0.0, 0.0]
range_noise_m = 0.01

[servo]
node_id = 1
counts_per_rev = 4096
gear_ratio = 50

[gps]
protocol = "novatel"
position_types = "NARROW_INT@0"
noise_scale = 1.0
antenna_m = [0.0, 0.0, 1.8]
error_model = "markov"          # or "white": then drop the <class>_ keys below
rtk_fixed_sigma_m = 0.02
rtk_fixed_time_constant_s = 30.0
rtk_float_sigma_m = 0.15
rtk_float_time_constant_s = 60.0
dgps_sigma_m = 0.4
dgps_time_constant_s = 60.0
sbas_sigma_m = 0.8
sbas_time_constant_s = 120.0
single_sigma_m = 1.5
single_time_constant_s = 120.0

[imu]
error_model = "ahrs"            # or "white": then drop the next three keys, angle_sigma_deg = 0.7
tilt_time_constant_s = 10.0
gyro_bias_walk_dps_per_sqrt_s = 0.0005
mag_disturbance_deg = 1.0
angle_sigma_deg = 0.047
rate_sigma_dps = 0.1
accel_sigma_mps2 = 0.02
declination_deg = 0.0

[devices]
lms = true
servo = true
gps = true
imu = true
)";
}

}  // namespace ugv::simworld
