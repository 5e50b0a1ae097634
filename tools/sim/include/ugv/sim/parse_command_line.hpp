// The command line of an ugv-sim subcommand, parsed the same way by every emulator: --help
// prints and ends with status 0, a bad flag prints one line and ends with status 2.
#pragma once

#include <optional>

#include <CLI/CLI.hpp>

namespace ugv::sim {

// std::nullopt: run the command; otherwise the status to end with.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv)
{
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    return std::nullopt;
}

}  // namespace ugv::sim
