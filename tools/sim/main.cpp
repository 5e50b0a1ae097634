// ugv-sim: the device emulators and the simulated vehicle. Each subcommand is registered by
// its own folder (see ugv/sim/command.hpp).
#include <cstdio>
#include <cstring>
#include <string>

#include "ugv/sim/command.hpp"

namespace ugv::sim {
std::map<std::string, Command>& commands()
{
    static std::map<std::string, Command> registry;
    return registry;
}
}  // namespace ugv::sim

static void usage(FILE* out)
{
    std::fprintf(out, "usage: ugv-sim COMMAND [options]   (ugv-sim COMMAND --help for its options)\ncommands:\n");
    for (const auto& [name, cmd] : ugv::sim::commands()) std::fprintf(out, "  %-10s %s\n", name.c_str(), cmd.summary.c_str());
}

int main(int argc, char** argv)
{
    if (argc < 2 || std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) {
        usage(argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    const auto it = ugv::sim::commands().find(argv[1]);
    if (it == ugv::sim::commands().end()) {
        std::fprintf(stderr, "ugv-sim: unknown command '%s'\n", argv[1]);
        usage(stderr);
        return 2;
    }
    std::string prog = std::string("ugv-sim ") + argv[1];
    argv[1] = prog.data();
    return it->second.main(argc - 1, argv + 1);
}
