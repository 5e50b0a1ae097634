// ugv-pose as a real process: --replay/--out determinism on a log written here, a config
// error, and live LCM input -> POSE at 10 Hz of data time.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>
#include <ugv/daemon_status_t.hpp>
#include <ugv/gps_fix_t.hpp>
#include <ugv/gps_velocity_t.hpp>
#include <ugv/imu_t.hpp>
#include <ugv/pose_t.hpp>

#include "run_helpers.hpp"

extern char** environ;

namespace fs = std::filesystem;
using namespace ugv::estimation;
using namespace ugv::estimation::synthetic;

namespace {

const char* kLiveUrl = "udpm://239.255.76.67:7901?ttl=0";

fs::path temp_dir(const std::string& name)
{
    const fs::path p = fs::temp_directory_path() / ("ugv-pose-test-" + name + "-" + std::to_string(getpid()));
    fs::remove_all(p);
    fs::create_directories(p);
    return p;
}

std::string bin(const std::string& program)
{
    const char* dir = std::getenv("UGV_BIN_DIR");
    return std::string(dir ? dir : UGV_BINARY_DIR "/bin") + "/" + program;
}

// Starts a program with stderr to a file; returns its pid.
pid_t spawn(const std::vector<std::string>& args, const fs::path& stderr_path)
{
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 2, stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    REQUIRE(rc == 0);
    return pid;
}

// Waits up to timeout for pid; returns its exit status, or -1 (and kills it) on timeout.
int wait_exit(pid_t pid, std::chrono::milliseconds timeout)
{
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid) {
            return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    return -1;
}

std::string slurp(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

ugv::gps_fix_t to_msg(const GpsFix& f, int64_t seq)
{
    ugv::gps_fix_t m{};
    m.utime = f.utime;
    m.seq = seq;
    m.gps_week = -1;
    m.gps_ms = -1;
    m.latitude = f.latitude_deg;
    m.longitude = f.longitude_deg;
    m.height = f.height_m;
    m.undulation = NAN;
    m.sigma_latitude = static_cast<float>(f.sigma_north_m);
    m.sigma_longitude = static_cast<float>(f.sigma_east_m);
    m.sigma_height = static_cast<float>(f.sigma_up_m);
    m.fix_quality = ugv::gps_fix_t::QUALITY_DGPS;
    m.satellites_used = 9;
    m.satellites_tracked = 11;
    m.differential_age = 1.0f;
    m.source = ugv::gps_fix_t::SOURCE_NOVATEL_BINARY;
    return m;
}

ugv::gps_velocity_t to_msg(const GpsVelocity& v, int64_t seq)
{
    ugv::gps_velocity_t m{};
    m.utime = v.utime;
    m.seq = seq;
    m.horizontal_speed = v.horizontal_speed_mps;
    m.track = v.track_rad;
    m.vertical_speed = v.vertical_speed_mps;
    m.latency = 0.0f;
    return m;
}

ugv::imu_t to_msg(const ImuSample& s, int64_t seq)
{
    ugv::imu_t m{};
    m.utime = s.utime;
    m.seq = seq;
    m.orientation[0] = s.orientation.w();
    m.orientation[1] = s.orientation.x();
    m.orientation[2] = s.orientation.y();
    m.orientation[3] = s.orientation.z();
    for (int i = 0; i < 3; ++i) {
        m.angular_rate[i] = s.rate_rps(i);
        m.acceleration[i] = s.accel_mps2(i);
        m.magnetic_field[i] = NAN;
    }
    m.roll = m.pitch = m.yaw = NAN;
    m.orientation_sigma = static_cast<float>(s.orientation_sigma_rad);
    m.valid = static_cast<int32_t>(ugv::imu_t::VALID_ORIENTATION) |
              static_cast<int32_t>(ugv::imu_t::VALID_ANGULAR_RATE) |
              static_cast<int32_t>(ugv::imu_t::VALID_ACCELERATION);
    return m;
}

// Calls publish(channel, message) for each synthetic input, in order.
template <typename Publish>
void for_each_message(const Run& run, Publish&& publish)
{
    int64_t seq_fix = 0, seq_vel = 0, seq_imu = 0;
    for (const Input& in : run.inputs) {
        if (const auto* f = std::get_if<GpsFix>(&in)) {
            publish("GPS_FIX", to_msg(*f, seq_fix++), f->utime);
        } else if (const auto* v = std::get_if<GpsVelocity>(&in)) {
            publish("GPS_VEL", to_msg(*v, seq_vel++), v->utime);
        } else {
            const auto& s = std::get<ImuSample>(in);
            publish("IMU", to_msg(s, seq_imu++), s.utime);
        }
    }
}

// bad_stamps: after every 97th input (all three kinds in turn), the same message again stamped with each of these
// (the log's event time stays that of the good one: a receiver's clock gone wrong).
void write_log(const fs::path& path, const Run& run, const std::vector<int64_t (*)(int64_t)>& bad_stamps = {})
{
    lcm::LogFile log(path.string(), "w");
    REQUIRE(log.good());
    int64_t n = 0, good = 0;
    for_each_message(run, [&](const char* channel, const auto& msg, int64_t utime) {
        const auto write = [&](const auto& m) {
            std::vector<uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
            m.encode(buf.data(), 0, static_cast<int>(buf.size()));
            lcm::LogEvent ev;
            ev.eventnum = n++;
            ev.timestamp = utime + 2'000;  // received 2 ms after the measurement
            ev.channel = channel;
            ev.datalen = static_cast<int32_t>(buf.size());
            ev.data = buf.data();
            REQUIRE(log.writeEvent(&ev) == 0);
        };
        write(msg);
        if (good++ % 97 == 0) {
            for (const auto stamp : bad_stamps) {
                auto bad = msg;
                bad.utime = stamp(utime);
                write(bad);
            }
        }
    });
}

std::vector<ugv::pose_t> read_poses(const fs::path& path)
{
    lcm::LogFile log(path.string(), "r");
    REQUIRE(log.good());
    std::vector<ugv::pose_t> out;
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel != "POSE") continue;
        ugv::pose_t p;
        REQUIRE(p.decode(ev->data, 0, ev->datalen) == ev->datalen);
        out.push_back(p);
    }
    return out;
}

void write_config(const fs::path& path, const std::string& extra = "")
{
    std::ofstream f(path);
    f << "pose_times = \"grid\"\n"
         "rate_hz = 10\n"
         "accel_noise = 0.05\n"
         "gyro_noise = 0.005\n"
         "gps_velocity_sigma_mps = 0.05\n"
         "gate_position_chi2 = 16.27\n"
      << extra << "\n[datum]\nlat = " << kTestDatum.latitude_deg << "\nlon = " << kTestDatum.longitude_deg
      << "\nheight = " << kTestDatum.height_m << "\n";
}

}  // namespace

TEST_CASE("--replay LOG --out LOG: bit-identical output, poses on the 100 ms grid near the truth")
{
    const fs::path dir = temp_dir("replay");
    const Trajectory t = circle(20.0, 3.0);
    const Run run = simulate(t, Noise{}, kTestDatum, 20.0, 11);
    write_log(dir / "in.log", run);
    write_config(dir / "pose.toml");

    for (const char* out : {"a.log", "b.log"}) {
        const pid_t pid = spawn({bin("ugv-pose"), "--config", (dir / "pose.toml").string(), "--replay",
                                 (dir / "in.log").string(), "--out", (dir / out).string()},
                                dir / (std::string(out) + ".err"));
        INFO(slurp(dir / (std::string(out) + ".err")));
        REQUIRE(wait_exit(pid, std::chrono::seconds(60)) == 0);
    }
    const std::string a = slurp(dir / "a.log"), b = slurp(dir / "b.log");
    REQUIRE(!a.empty());
    CHECK(a == b);

    const std::vector<ugv::pose_t> poses = read_poses(dir / "a.log");
    // 20 s of data; the last 150 ms stay in the reorder buffer at the end of the log.
    REQUIRE(poses.size() >= 198);
    REQUIRE(poses.size() <= 200);
    for (std::size_t i = 0; i < poses.size(); ++i) {
        CHECK(poses[i].seq == static_cast<int64_t>(i));
        CHECK(poses[i].utime % 100'000 == 0);
        if (i > 0) CHECK(poses[i].utime - poses[i - 1].utime == 100'000);
        CHECK(poses[i].datum_latitude == kTestDatum.latitude_deg);
        CHECK(poses[i].datum_height == kTestDatum.height_m);
    }
    const ugv::pose_t& last = poses.back();
    CHECK(last.status == ugv::pose_t::STATUS_OK);
    const Truth truth = truth_at(t, run, last.utime);
    CHECK(std::hypot(last.position[0] - truth.position.x(), last.position[1] - truth.position.y()) < 0.5);
    CHECK(std::fabs(ugv::geometry::wrap_angle(last.yaw - truth.yaw)) < 0.02);
    CHECK(last.position_covariance[0] > 0.0);
    CHECK(last.position_covariance[1] == last.position_covariance[3]);  // symmetric, row-major
    CHECK(last.orientation_covariance[8] > 0.0);
    CHECK(last.orientation_covariance[8] < 1e-4);  // yaw sigma < 0.01 rad once moving
    fs::remove_all(dir);
}

TEST_CASE("--replay refuses stamps far from the log's event time: the poses are those of the clean log")
{
    const fs::path dir = temp_dir("stamps");
    const Run run = simulate(circle(20.0, 3.0), Noise{}, kTestDatum, 20.0, 11);
    write_log(dir / "clean.log", run);
    write_log(dir / "dirty.log", run,
              {[](int64_t) { return std::numeric_limits<int64_t>::max(); },
               [](int64_t t) { return t + int64_t{365} * 86'400'000'000; },
               [](int64_t) { return std::numeric_limits<int64_t>::min(); },
               [](int64_t t) { return t - int64_t{3'600'000'000}; }});
    write_config(dir / "pose.toml");
    for (const char* name : {"clean", "dirty"}) {
        const pid_t pid = spawn({bin("ugv-pose"), "--config", (dir / "pose.toml").string(), "--replay",
                                 (dir / (std::string(name) + ".log")).string(), "--out",
                                 (dir / (std::string(name) + ".out")).string()},
                                dir / (std::string(name) + ".err"));
        INFO(slurp(dir / (std::string(name) + ".err")));
        REQUIRE(wait_exit(pid, std::chrono::seconds(60)) == 0);
    }
    const std::vector<ugv::pose_t> clean = read_poses(dir / "clean.out"), dirty = read_poses(dir / "dirty.out");
    REQUIRE(clean.size() >= 198);
    REQUIRE(dirty.size() == clean.size());
    for (std::size_t i = 0; i < clean.size(); ++i) {
        std::vector<uint8_t> a(static_cast<std::size_t>(clean[i].getEncodedSize())), b(a.size());
        clean[i].encode(a.data(), 0, static_cast<int>(a.size()));
        dirty[i].encode(b.data(), 0, static_cast<int>(b.size()));
        CHECK(a == b);
    }
    const std::string err = slurp(dir / "dirty.err");
    for (const char* channel : {"GPS_FIX:", "GPS_VEL:", "IMU:"}) {
        CHECK(err.find(std::string(channel) + " message stamped 9223372036854775807") != std::string::npos);
    }
    fs::remove_all(dir);
}

TEST_CASE("a bad config key exits 2 with one line naming it")
{
    const fs::path dir = temp_dir("config");
    {
        std::ofstream f(dir / "bad.toml");
        f << "rate_hz = 0.0\n";
    }
    // --replay needs an existing file (CLI11 checks); the config is refused before it is read.
    const pid_t pid = spawn({bin("ugv-pose"), "--config", (dir / "bad.toml").string(), "--replay",
                             (dir / "bad.toml").string(), "--out", (dir / "o.log").string()},
                            dir / "err");
    CHECK(wait_exit(pid, std::chrono::seconds(20)) == 2);
    const std::string err = slurp(dir / "err");
    CHECK(err.find("bad.toml: rate_hz: ") != std::string::npos);
    {
        std::ofstream f(dir / "bad2.toml");
        f << "datum = \"somewhere\"\n";
    }
    const pid_t pid2 = spawn({bin("ugv-pose"), "--config", (dir / "bad2.toml").string(), "--replay",
                              (dir / "bad2.toml").string(), "--out", (dir / "o.log").string()},
                             dir / "err2");
    CHECK(wait_exit(pid2, std::chrono::seconds(20)) == 2);
    CHECK(slurp(dir / "err2").find("bad2.toml: datum: ") != std::string::npos);
    fs::remove_all(dir);
}

namespace {

struct LiveCapture
{
    std::vector<ugv::pose_t> poses;
    std::vector<ugv::daemon_status_t> statuses;
    void on_pose(const lcm::ReceiveBuffer*, const std::string&, const ugv::pose_t* m) { poses.push_back(*m); }
    void on_status(const lcm::ReceiveBuffer*, const std::string&, const ugv::daemon_status_t* m)
    {
        statuses.push_back(*m);
    }
};

int64_t wall_utime()
{
    return std::chrono::duration_cast<std::chrono::microseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

}  // namespace

TEST_CASE("live: synthetic GPS + IMU on LCM give POSE at 10 Hz and STATUS_POSE counters")
{
    lcm::LCM lcm(kLiveUrl);
    REQUIRE(lcm.good());
    LiveCapture cap;
    lcm.subscribe("POSE", &LiveCapture::on_pose, &cap);
    lcm.subscribe("STATUS_POSE", &LiveCapture::on_status, &cap);

    const fs::path dir = temp_dir("live");
    write_config(dir / "pose.toml");
    const pid_t pid = spawn({bin("ugv-pose"), "--config", (dir / "pose.toml").string(), "--lcm-url", kLiveUrl},
                            dir / "err");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let it subscribe

    // 5 s of data, published in real time, stamped from now.
    const int64_t start = wall_utime();
    const Run run = simulate(circle(20.0, 3.0), Noise{}, kTestDatum, 5.0, 12, start);
    for_each_message(run, [&](const char* channel, const auto& msg, int64_t utime) {
        while (wall_utime() < utime) {
            lcm.handleTimeout(1);
        }
        lcm.publish(channel, &msg);
    });
    const auto drain_until = std::chrono::steady_clock::now() + std::chrono::milliseconds(1500);
    while (std::chrono::steady_clock::now() < drain_until) {
        lcm.handleTimeout(50);
    }
    kill(pid, SIGTERM);
    const int rc = wait_exit(pid, std::chrono::seconds(5));
    INFO(slurp(dir / "err"));
    CHECK(rc == 0);

    // 5 s of data at 10 Hz, less the reorder buffer at the end; multicast may drop a few
    // on a loaded machine, so the spacing is checked where consecutive.
    CHECK(cap.poses.size() >= 40);
    CHECK(cap.poses.size() <= 50);
    int consecutive = 0;
    for (std::size_t i = 0; i < cap.poses.size(); ++i) {
        CHECK(cap.poses[i].utime % 100'000 == 0);
        if (i > 0 && cap.poses[i].seq == cap.poses[i - 1].seq + 1) {
            CHECK(cap.poses[i].utime - cap.poses[i - 1].utime == 100'000);
            ++consecutive;
        }
    }
    CHECK(consecutive >= 35);
    REQUIRE(!cap.statuses.empty());
    const ugv::daemon_status_t& st = cap.statuses.back();
    CHECK(st.name == "ugv-pose");
    int64_t gps_used = -1, imu_used = -1;
    for (int i = 0; i < st.ncounters; ++i) {
        if (st.counter_names[i] == "gps_used") gps_used = st.counter_values[i];
        if (st.counter_names[i] == "imu_used") imu_used = st.counter_values[i];
    }
    CHECK(gps_used > 10);
    CHECK(imu_used > 100);
    fs::remove_all(dir);
}

TEST_CASE("live: STATUS_POSE is RUNNING while POSE flows, DEGRADED when the inputs stop, RUNNING when they resume")
{
    // Issue 23, "STATUS tells the truth": port 7743.
    const char* url = "udpm://239.255.76.67:7743?ttl=0";
    lcm::LCM lcm(url);
    REQUIRE(lcm.good());
    LiveCapture cap;
    lcm.subscribe("POSE", &LiveCapture::on_pose, &cap);
    lcm.subscribe("STATUS_POSE", &LiveCapture::on_status, &cap);
    const fs::path dir = temp_dir("status");
    write_config(dir / "pose.toml");
    const pid_t pid = spawn({bin("ugv-pose"), "--config", (dir / "pose.toml").string(), "--lcm-url", url}, dir / "err");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // let it subscribe

    // 14 s of a vehicle on a circle, in real time, stamped from now; nothing from 5 s to 9 s.
    const auto state_now = [&] { return cap.statuses.empty() ? int8_t{-1} : cap.statuses.back().state; };
    const int64_t start = wall_utime();
    const Run run = simulate(circle(20.0, 3.0), Noise{}, kTestDatum, 14.0, 12, start);
    bool running_before = false, degraded_in_gap = false, running_after = false;
    std::string gap_error;
    for_each_message(run, [&](const char* channel, const auto& msg, int64_t utime) {
        while (wall_utime() < utime) {
            lcm.handleTimeout(1);
            const double t = static_cast<double>(wall_utime() - start) * 1e-6;
            const int8_t s = state_now();
            if (t < 5.0) running_before = running_before || s == ugv::daemon_status_t::STATE_RUNNING;
            if (t > 5.0 && t < 9.0 && s == ugv::daemon_status_t::STATE_DEGRADED && !degraded_in_gap) {
                degraded_in_gap = true;
                gap_error = cap.statuses.back().last_error;
            }
            if (t > 9.0) running_after = running_after || s == ugv::daemon_status_t::STATE_RUNNING;
        }
        const double t = static_cast<double>(utime - start) * 1e-6;
        if (t < 5.0 || t >= 9.0) lcm.publish(channel, &msg);
    });
    kill(pid, SIGTERM);
    const int rc = wait_exit(pid, std::chrono::seconds(5));
    INFO(slurp(dir / "err"));
    CHECK(rc == 0);
    CHECK(running_before);
    CHECK(degraded_in_gap);
    CHECK(gap_error.find("no POSE for 2.0 s") != std::string::npos);
    CHECK(running_after);
    fs::remove_all(dir);
}
