// Foxglove's npm packages (tests/foxglove/package-lock.json) installed with `npm ci` into the
// build folder, beside the check scripts. Where node, npm or the packages cannot be had, the
// test exits 77 (skipped) and says why.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

#include "ugv_test/process.hpp"

namespace ugv::test {

[[noreturn]] inline void skip_test(const std::string& test, const std::string& why)
{
    std::printf("SKIPPED %s: %s\n", test.c_str(), why.c_str());
    std::fflush(stdout);
    std::exit(77);
}

inline std::string which(const std::string& program)
{
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    for (std::string d; std::getline(dirs, d, ':');) {
        const std::filesystem::path p = std::filesystem::path(d) / program;
        if (!d.empty() && access(p.c_str(), X_OK) == 0) return p.string();
    }
    return {};
}

// The folder with the packages and the check scripts; skips the test when they cannot be had.
inline const std::string& node_dir(const std::string& test)
{
    namespace fs = std::filesystem;
    static const std::string dir = [&] {
        const std::string node = which("node"), npm = which("npm");
        if (node.empty() || npm.empty()) skip_test(test, "no node or npm on the PATH (tools/install-deps installs Debian's)");
        const fs::path src = fs::path(UGV_SOURCE_DIR) / "tests/foxglove";
        const fs::path dst = fs::path(UGV_BINARY_DIR) / "tests/foxglove-node";
        fs::create_directories(dst);
        const bool fresh = fs::exists(dst / "node_modules/@foxglove/ws-protocol") && fs::exists(dst / "package-lock.json") &&
                           read_file(dst / "package-lock.json") == read_file(src / "package-lock.json");
        for (const auto& f : fs::directory_iterator(src))
            if (f.path().extension() == ".json" || f.path().extension() == ".mjs")
                fs::copy_file(f.path(), dst / f.path().filename(), fs::copy_options::overwrite_existing);
        if (!fresh) {
            const std::string log = (dst / "npm-ci.log").string();
            const int rc = run({npm, "ci", "--prefix", dst.string(), "--ignore-scripts", "--no-audit", "--no-fund"}, log,
                               log, 180);
            if (rc != 0) skip_test(test, "npm ci failed (no npm registry?), see " + log);
        }
        return dst.string();
    }();
    return dir;
}

}  // namespace ugv::test
