// ugv-foxglove as a test's process: its config on the test's TCP port, and the wait until it listens.
#pragma once

#include <string>

#include "ugv_test/process.hpp"

namespace ugv::test {

inline std::string bridge_config(const TempDir& dir, int port, const std::string& extra = "")
{
    const std::string path = dir / "foxglove.toml";
    write_file(path, "address = \"127.0.0.1\"\nport = " + std::to_string(port) + "\n" + extra);
    return path;
}

// True once the daemon says it serves (it has bound its port).
inline bool wait_serving(Process& bridge, double timeout_s = 20)
{
    return wait_until([&] { return bridge.err().find("serving") != std::string::npos; }, timeout_s);
}

}  // namespace ugv::test
