// ugv-sim subcommands. Each emulator (tools/sim/<device>/) registers one with
//   UGV_SIM_COMMAND("lms", "SICK LMS 2xx on a pseudo-terminal", lms_main);
// and `ugv-sim lms --pty PATH ...` calls lms_main(argc, argv) with argv[0] = "ugv-sim lms".
// Stop signals: ugv/runtime/stop_signals.hpp, as in every daemon and tool.
#pragma once

#include <map>
#include <string>

namespace ugv::sim {

using CommandMain = int (*)(int argc, char** argv);

struct Command
{
    std::string summary;
    CommandMain main;
};

std::map<std::string, Command>& commands();

struct CommandRegistration
{
    CommandRegistration(const char* name, const char* summary, CommandMain fn)
    {
        commands()[name] = Command{summary, fn};
    }
};

}  // namespace ugv::sim

#define UGV_SIM_COMMAND(name, summary, fn) \
    static const ::ugv::sim::CommandRegistration ugv_sim_registration_##fn(name, summary, fn)
