// Running ugv-calibrate from a test: its exit status and output, and a parameter of its JSON.
#pragma once

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "ugv_test/process.hpp"

namespace ugv::test {

struct CalibrateRun
{
    int rc = -1;
    std::string out, err;
};

// ugv-calibrate ARGS (the command first), its output kept in dir.
inline CalibrateRun run_calibrate(const TempDir& dir, std::vector<std::string> args)
{
    args.insert(args.begin(), bin("ugv-calibrate"));
    CalibrateRun r;
    r.rc = run(args, dir / "out.txt", dir / "err.txt", 50);
    r.out = read_file(dir / "out.txt");
    r.err = read_file(dir / "err.txt");
    return r;
}

// The value of parameter `key` in the JSON line (`"key": {"value": V, ...}`).
inline double json_value(const std::string& json, const std::string& key)
{
    const auto at = json.find("\"" + key + "\": {\"value\": ");
    REQUIRE(at != std::string::npos);
    return std::stod(json.substr(at + key.size() + 13));
}

}  // namespace ugv::test
