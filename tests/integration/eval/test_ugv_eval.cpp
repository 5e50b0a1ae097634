// ugv-eval on logs written here: `compare --truth` against a height field in the simulator's
// file format, and `diff` between the maps of two logs.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ugv/simworld/height_field.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/pose_t.hpp"
#include "ugv/sim_truth_t.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv_test/encoded.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int64_t kUtime = 1'700'000'000'000'000;

// A 4 x 4 map of 1 m cells from (0, -2) at the identity pose: cell (i, j) covers x in
// [i, i+1), y in [j-2, j-1); every cell at height z.
terrain_map_t flat_map(float z)
{
    terrain_map_t m{};
    m.utime = kUtime;
    m.pose.utime = kUtime;
    m.pose.orientation[0] = 1.0;
    m.resolution = 1.0f;
    m.nx = m.ny = 4;
    m.origin_x = 0.0f;
    m.origin_y = -2.0f;
    m.ncells = 16;
    m.mean_z.assign(16, z);
    m.variance_z.assign(16, 0.01f);
    m.count.assign(16, 5);
    m.max_z.assign(16, z);
    m.min_z.assign(16, z);
    m.age_s.assign(16, 0.0f);
    return m;
}

std::string write_log(const test::TempDir& dir, const std::string& name, const terrain_map_t& m)
{
    const std::string path = dir / name;
    lcm::LogFile log(path, "w");
    test::write_event(log, kUtime, "TERRAIN_MAP", m);
    return path;
}

int eval(const test::TempDir& dir, std::vector<std::string> args, std::string& out)
{
    args.insert(args.begin(), test::bin("ugv-eval"));
    const int rc = test::run(args, dir / "out.txt", dir / "err.txt", 30);
    out = test::read_file(dir / "out.txt") + test::read_file(dir / "err.txt");
    return rc;
}

}  // namespace

TEST_CASE("ugv-eval compare --truth: bias and RMSE against the simulator's height field, edges left out")
{
    test::TempDir dir;
    // Truth: flat at 0 with a 1 m step along x >= 2 (cells i = 2, 3 are 1 m high).
    simworld::HeightField truth(-1.0, -3.0, 0.1, 60, 60, 0.0f);
    for (int i = 30; i < 60; ++i)
        for (int j = 0; j < 60; ++j) truth.at(i, j) = 1.0f;
    test::write_file(dir / "truth.hf", simworld::encode_height_field(truth));
    terrain_map_t m = flat_map(0.02f);
    for (int i = 2; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m.mean_z[static_cast<std::size_t>(i * 4 + j)] = 1.02f;
    const std::string log = write_log(dir, "map.lcm", m);
    std::string out;
    REQUIRE(eval(dir, {"compare", log, "--truth", dir / "truth.hf"}, out) == 0);
    CHECK(out.find("\"known\": 16") != std::string::npos);
    CHECK(out.find("\"bias_m\": 0.02000") != std::string::npos);
    CHECK(out.find("\"rmse_m\": 0.02000") != std::string::npos);
    // Cell centres at x = 1.5 and 2.5 are within 0.6 m of the step at x = 2: left out.
    REQUIRE(eval(dir, {"compare", log, "--truth", dir / "truth.hf", "--exclude-edges", "0.6"}, out) == 0);
    CHECK(out.find("\"known\": 8") != std::string::npos);
    // Not a height field: one line, exit 2.
    test::write_file(dir / "bad.hf", "P5\n");
    CHECK(eval(dir, {"compare", log, "--truth", dir / "bad.hf"}, out) == 2);
    CHECK(out.find("not a height field") != std::string::npos);
}

TEST_CASE("ugv-eval diff: equal maps pass at zero tolerance, a changed cell is found")
{
    test::TempDir dir;
    const std::string a = write_log(dir, "a.lcm", flat_map(0.5f));
    const std::string same = write_log(dir, "same.lcm", flat_map(0.5f));
    terrain_map_t changed = flat_map(0.5f);
    changed.mean_z[5] = 0.55f;
    changed.mean_z[6] = NAN;
    const std::string c = write_log(dir, "c.lcm", changed);
    std::string out;
    CHECK(eval(dir, {"diff", a, same, "--max-dz", "0"}, out) == 0);
    CHECK(out.find("\"cells_both\": 16") != std::string::npos);
    CHECK(eval(dir, {"diff", a, c, "--max-dz", "0.01"}, out) == 1);
    CHECK(out.find("\"cells_both\": 15") != std::string::npos);
    CHECK(out.find("\"only_a\": 1") != std::string::npos);
    CHECK(eval(dir, {"diff", a, c, "--max-dz", "0.06"}, out) == 0);
}

TEST_CASE("ugv-eval: map messages whose bytes lie are skipped and said, never decoded")
{
    // A map whose ncells says 2^31 - 1 (lcm-gen's decode would try to allocate 24 GB), a
    // truncated map, then a good one: both commands use the good one.
    test::TempDir dir;
    const terrain_map_t good = flat_map(0.5f);
    std::vector<uint8_t> lying = test::encoded(good);
    const std::size_t ncells_at = lying.size() - 16 * 4 * 6 - 4;  // the six arrays follow ncells
    REQUIRE(lying[ncells_at + 3] == 16);
    lying[ncells_at] = 0x7f;
    lying[ncells_at + 1] = lying[ncells_at + 2] = lying[ncells_at + 3] = 0xff;
    std::vector<uint8_t> truncated = test::encoded(good);
    truncated.resize(truncated.size() / 2);
    const std::string bad = dir / "bad.lcm";
    {
        lcm::LogFile log(bad, "w");
        for (auto* bytes : {&lying, &truncated}) {
            lcm::LogEvent ev{};
            ev.timestamp = kUtime;
            ev.channel = "TERRAIN_MAP";
            ev.datalen = static_cast<int32_t>(bytes->size());
            ev.data = bytes->data();
            log.writeEvent(&ev);
        }
        test::write_event(log, kUtime, "TERRAIN_MAP", good);
    }
    const std::string a = write_log(dir, "a.lcm", good);
    std::string out;
    CHECK(eval(dir, {"diff", a, bad, "--max-dz", "0"}, out) == 0);
    CHECK(out.find("\"cells_both\": 16") != std::string::npos);
    simworld::HeightField truth(-1.0, -3.0, 0.1, 60, 60, 0.5f);
    test::write_file(dir / "truth.hf", simworld::encode_height_field(truth));
    CHECK(eval(dir, {"compare", bad, "--truth", dir / "truth.hf"}, out) == 0);
    CHECK(out.find("\"known\": 16") != std::string::npos);
    CHECK(out.find("2 message(s) on TERRAIN_MAP in " + bad + " are not terrain maps (skipped)") != std::string::npos);
}

TEST_CASE("ugv-eval coverage: the known share of the area ahead, over the window after the turn")
{
    test::TempDir dir;
    const std::string path = dir / "turn.lcm";
    {
        lcm::LogFile log(path, "w");
        // Four maps 1 s apart, heading east, 45, 90 and 90 deg left; each knows fewer cells
        // in x 1..3 (cells i = 1, 2: 8 cells of 1 m within 2 m of the centre line): 8, 6, 4, 2.
        for (int k = 0; k < 4; ++k) {
            terrain_map_t m = flat_map(0.0f);
            m.utime = kUtime + k * 1'000'000;
            m.pose.utime = m.utime;
            const double yaw = std::min(k, 2) * M_PI / 4;
            m.pose.orientation[0] = std::cos(yaw / 2);
            m.pose.orientation[3] = std::sin(yaw / 2);
            for (int j = 0; j < 2 * k; ++j) m.mean_z[static_cast<std::size_t>(4 + (j % 2) * 4 + j / 2)] = NAN;
            test::write_event(log, m.utime, "TERRAIN_MAP", m);
        }
    }
    std::string out;
    REQUIRE(eval(dir, {"coverage", path, "--ahead", "1,3", "--half-width", "2", "--turn", "80", "--window", "5"}, out) == 0);
    // The turn: the map at 90 deg (the third); the window holds it and the fourth: 4 and 2 of 8.
    CHECK(out.find("\"maps\": 2,") != std::string::npos);
    CHECK(out.find("\"turn_utime\": " + std::to_string(kUtime + 2'000'000)) != std::string::npos);
    CHECK(out.find("\"area_cells\": 8,") != std::string::npos);
    CHECK(out.find("\"mean_known\": 3.0,") != std::string::npos);
    CHECK(out.find("\"mean_coverage\": 0.3750") != std::string::npos);
    CHECK(out.find("\"min_coverage\": 0.2500") != std::string::npos);
    REQUIRE(eval(dir, {"coverage", path, "--ahead", "1,3", "--half-width", "2", "--all"}, out) == 0);
    CHECK(out.find("\"turned_deg\": 45.0, \"cells\": 8, \"known\": 6") != std::string::npos);
    // No turn that far: exit 1 with a line saying so; a bad area: exit 2.
    CHECK(eval(dir, {"coverage", path, "--turn", "120"}, out) == 1);
    CHECK(out.find("no map turned 120 deg") != std::string::npos);
    CHECK(eval(dir, {"coverage", path, "--ahead", "3,1"}, out) == 2);
    CHECK(out.find("--ahead 3,1: X1 must be greater than X0") != std::string::npos);
}

TEST_CASE("ugv-eval attitude: the IMU's and the pose's errors against SIM_TRUTH, standing, straight, turning")
{
    // Truth at 100 Hz: standing 0-1 s, straight east at 2 m/s 1-2 s, turning left at 10 deg/s
    // 2-4 s. The IMU (50 Hz) is off by +1 deg in roll while turning and -0.5 deg in pitch
    // while straight; the pose by +0.2 deg in roll throughout (and one initialising pose far
    // off, not scored). No sample within 0.15 s of a change of motion (the yaw rate is taken
    // over +/- 0.1 s).
    test::TempDir dir;
    const std::string path = dir / "att.lcm";
    constexpr double kDeg = M_PI / 180.0;
    auto yaw_at = [](double t) { return t < 2 ? 0.0 : 10.0 * kDeg * (t - 2); };
    auto x_at = [](double t) { return t < 1 ? 0.0 : 2.0 * (std::min(t, 2.0) - 1); };
    auto truth_roll = [](double t) { return 0.01 * std::sin(t); };  // a little terrain
    {
        lcm::LogFile log(path, "w");
        for (int k = 0; k <= 400; ++k) {
            const double t = k * 0.01;
            sim_truth_t s{};
            s.utime = kUtime + k * 10'000;
            s.position[0] = x_at(t);
            s.velocity[0] = t >= 1 ? 2.0 * std::cos(yaw_at(t)) : 0.0;
            s.velocity[1] = t >= 1 ? 2.0 * std::sin(yaw_at(t)) : 0.0;
            s.roll = truth_roll(t);
            s.pitch = -0.02;
            s.yaw = yaw_at(t);
            s.orientation[0] = 1.0;
            s.scenario = "test";
            test::write_event(log, s.utime, "SIM_TRUTH", s);
        }
        auto near_change = [](double t) { return std::abs(t - 1) < 0.15 || std::abs(t - 2) < 0.15; };
        for (int k = 0; k <= 200; ++k) {
            const double t = k * 0.02;
            if (near_change(t)) continue;
            imu_t m{};
            m.utime = kUtime + k * 20'000;
            m.valid = imu_t::VALID_EULER;
            m.roll = truth_roll(t) + (t > 2 ? 1.0 * kDeg : 0.0);
            m.pitch = -0.02 + (t > 1 && t < 2 ? -0.5 * kDeg : 0.0);
            m.yaw = yaw_at(t);
            test::write_event(log, m.utime, "IMU", m);
            pose_t p{};
            p.utime = m.utime;
            p.status = k == 0 ? pose_t::STATUS_INITIALIZING : pose_t::STATUS_OK;
            p.roll = truth_roll(t) + (k == 0 ? 0.5 : 0.2 * kDeg);
            p.pitch = -0.02;
            p.yaw = yaw_at(t);
            test::write_event(log, p.utime, "POSE", p);
        }
    }
    std::string out;
    REQUIRE(eval(dir, {"attitude", path}, out) == 0);
    auto line = [&](const std::string& source, const std::string& motion) {
        const std::string key = "{\"source\": \"" + source + "\", \"motion\": \"" + motion + "\"";
        const auto at = out.find(key);
        return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
    };
    INFO(out);
    CHECK(line("IMU", "turning").find("\"roll_rms_deg\": 1.0000, \"roll_max_deg\": 1.0000, \"pitch_rms_deg\": 0.0000") !=
          std::string::npos);
    CHECK(line("IMU", "straight").find("\"roll_rms_deg\": 0.0000, \"roll_max_deg\": 0.0000, \"pitch_rms_deg\": 0.5000") !=
          std::string::npos);
    CHECK(line("IMU", "standing").find("\"roll_max_deg\": 0.0000, \"pitch_rms_deg\": 0.0000") != std::string::npos);
    // 201 IMU samples less 2 x 15 near the changes (t = 0.86 .. 1.14 and 1.86 .. 2.14).
    CHECK(line("IMU", "all").find("\"samples\": 171") != std::string::npos);
    CHECK(line("POSE", "all").find("\"samples\": 170, \"roll_rms_deg\": 0.2000, \"roll_max_deg\": 0.2000") !=
          std::string::npos);
    CHECK(out.find("1 pose(s) initialising") != std::string::npos);

    // --pose-log: the pose from a second log (a replay), the truth and the IMU from the first;
    // the first log's own poses are not scored.
    const std::string replayed = dir / "replayed.lcm";
    {
        lcm::LogFile log(replayed, "w");
        for (int k = 1; k <= 200; ++k) {
            const double t = k * 0.02;
            if (std::abs(t - 1) < 0.15 || std::abs(t - 2) < 0.15) continue;
            pose_t p{};
            p.utime = kUtime + k * 20'000;
            p.status = pose_t::STATUS_OK;
            p.roll = truth_roll(t) + 0.4 * kDeg;
            p.pitch = -0.02;
            p.yaw = yaw_at(t);
            test::write_event(log, p.utime, "POSE", p);
        }
    }
    REQUIRE(eval(dir, {"attitude", path, "--pose-log", replayed}, out) == 0);
    CHECK(line("IMU", "all").find("\"samples\": 171") != std::string::npos);
    CHECK(line("POSE", "all").find("\"samples\": 170, \"roll_rms_deg\": 0.4000, \"roll_max_deg\": 0.4000") !=
          std::string::npos);

    // A log without the truth cannot be scored.
    const std::string bare = dir / "bare.lcm";
    {
        lcm::LogFile log(bare, "w");
        imu_t m{};
        m.utime = kUtime;
        m.valid = imu_t::VALID_EULER;
        test::write_event(log, m.utime, "IMU", m);
    }
    CHECK(eval(dir, {"attitude", bare}, out) == 1);
    CHECK(out.find("no SIM_TRUTH") != std::string::npos);
}
