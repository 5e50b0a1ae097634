// ugv-udev-setup: which USB serial adapter is which device, for udev's /dev/ugv/<role> names.
//   ugv-udev-setup                         lists the attached adapters and asks each one's role
//   ugv-udev-setup --role lms-front=0403:6001:A50285BI --role gps=ttyUSB1
//                                          sets roles from flags (an id, or an attached tty)
//   ugv-udev-setup --list                  the attached adapters and their roles
//   ugv-udev-setup --remove gps            drops a role
//   ugv-udev-setup --lookup 0403:6001:A50285BI   for the udev rule: prints UGV_ROLE=<role>
// Roles go to /etc/ugv/devices.conf (--config); --print shows the result instead of writing.
// Exit 0; 1 when nothing could be done (no adapters, input ended); 2 for a bad flag or file.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "ugv/io/whole_file.hpp"
#include "ugv/runtime/config.hpp"
#include "ugv/udev_setup/device_roles.hpp"
#include "ugv/udev_setup/usb_adapters.hpp"

namespace {

using namespace ugv::udev_setup;
constexpr const char* kDefaultConfig = "/etc/ugv/devices.conf";

// The roles in path; none when it does not exist yet. Throws ConfigError.
std::vector<DeviceRole> load_roles(const std::string& path)
{
    std::vector<uint8_t> bytes;
    std::string why;
    switch (ugv::io::read_regular_file(path, 1 << 20, bytes, why)) {
    case ugv::io::ReadResult::ok: return parse_roles(std::string(bytes.begin(), bytes.end()), path);
    case ugv::io::ReadResult::missing: return {};
    default: throw ugv::runtime::ConfigError(path, "-", why);
    }
}

// SPEC of --role: an id, or the name of an attached tty whose id is read from sysfs.
UsbId resolve(const std::string& spec, const std::vector<SerialAdapter>& adapters, const std::string& sysfs)
{
    if (spec.find(':') != std::string::npos) return parse_usb_id(spec);
    const std::string tty = std::filesystem::path(spec).filename().string();
    for (const auto& a : adapters)
        if (a.tty == tty) return a.id;
    throw std::invalid_argument("'" + spec + "' is neither VENDOR:PRODUCT[:SERIAL] nor an attached USB serial adapter (" +
                                std::to_string(adapters.size()) + " found in " + sysfs + "/class/tty)");
}

// Asks each attached adapter's role on stdin. Empty keeps the current role, '-' drops it.
// Returns false when the input ended before every adapter had an answer.
bool ask_roles(const std::vector<SerialAdapter>& adapters, std::vector<DeviceRole>& roles)
{
    for (const auto& a : adapters) {
        const auto current = lookup_role(roles, a.id);
        while (true) {
            std::cout << describe(a) << "\n  role (e.g. lms-front, gps, imu; Enter " << (current ? "keeps '" + *current + "'" : "skips")
                      << ", '-' drops it): " << std::flush;
            std::string answer;
            if (!std::getline(std::cin, answer)) return false;
            answer.erase(0, answer.find_first_not_of(" \t"));
            answer.erase(answer.find_last_not_of(" \t\r") + 1);
            if (answer.empty()) break;
            if (answer == "-") {
                std::erase_if(roles, [&](const DeviceRole& r) { return lookup_role({r}, a.id).has_value(); });
                break;
            }
            try {
                check_role_name(answer);
                // The adapter's exact id; a role it held under another id moves to this one.
                std::erase_if(roles, [&](const DeviceRole& r) { return r.role != answer && r.id.vendor == a.id.vendor &&
                                                                       r.id.product == a.id.product && r.id.serial == a.id.serial; });
                roles = merge_roles(std::move(roles), {DeviceRole{answer, a.id}});
                break;
            } catch (const std::invalid_argument& e) {
                std::cout << "  " << e.what() << "\n";
            }
        }
    }
    return true;
}

}  // namespace

int main(int argc, char** argv)
{
    std::string config = kDefaultConfig, sysfs = "/sys", lookup;
    std::vector<std::string> role_flags, removals;
    bool list = false, print = false, no_trigger = false;
    CLI::App app{"ugv-udev-setup: names USB serial adapters /dev/ugv/<role> (udev)"};
    app.set_version_flag("--version", std::string("ugv-udev-setup ") + UGV_VERSION);
    app.add_option("--role", role_flags, "ROLE=VENDOR:PRODUCT[:SERIAL] or ROLE=ttyUSB0 (repeatable)");
    app.add_option("--remove", removals, "drop ROLE (repeatable)");
    app.add_flag("--list", list, "list the attached adapters and their roles");
    app.add_option("--lookup", lookup, "VENDOR:PRODUCT:SERIAL: print UGV_ROLE=<role> (used by the udev rule)");
    app.add_option("--config", config, "the roles file")->capture_default_str();
    app.add_option("--sysfs", sysfs, "where sysfs is (a fake tree in tests)")->capture_default_str();
    app.add_flag("--print", print, "print the roles file instead of writing it");
    app.add_flag("--no-trigger", no_trigger, "do not ask udev to apply the roles to attached adapters");
    CLI11_PARSE(app, argc, argv);

    try {
        auto roles = load_roles(config);
        if (!lookup.empty()) {
            // udev passes ID_SERIAL_SHORT, empty for an adapter without a serial number.
            const auto c2 = lookup.find(':', lookup.find(':') + 1);
            UsbId id = parse_usb_id(lookup.substr(0, c2));
            if (c2 != std::string::npos) id.serial = lookup.substr(c2 + 1);
            if (const auto role = lookup_role(roles, id)) std::cout << "UGV_ROLE=" << *role << "\n";
            return 0;
        }
        const auto adapters = list_serial_adapters(sysfs);
        if (list) {
            if (adapters.empty()) std::cout << "no USB serial adapters in " << sysfs << "/class/tty\n";
            for (const auto& a : adapters) {
                const auto role = lookup_role(roles, a.id);
                std::cout << describe(a) << "  -> " << (role ? "/dev/ugv/" + *role : "no role") << "\n";
            }
            for (const auto& r : roles) {
                bool attached = false;
                for (const auto& a : adapters) attached = attached || lookup_role({r}, a.id).has_value();
                if (!attached) std::cout << r.role << ": " << format_usb_id(r.id) << " is not attached\n";
            }
            return 0;
        }
        if (role_flags.empty() && removals.empty()) {
            if (adapters.empty()) {
                std::cerr << "ugv-udev-setup: no USB serial adapters in " << sysfs << "/class/tty; plug them in or use --role\n";
                return 1;
            }
            if (!ask_roles(adapters, roles)) {
                std::cerr << "ugv-udev-setup: input ended; " << config << " left as it was\n";
                return 1;
            }
        }
        for (const auto& name : removals) {
            if (std::erase_if(roles, [&](const DeviceRole& r) { return r.role == name; }) == 0)
                throw std::invalid_argument("--remove " + name + ": no such role in " + config);
        }
        std::vector<DeviceRole> changes;
        for (const auto& flag : role_flags) {
            const auto eq = flag.find('=');
            if (eq == std::string::npos) throw std::invalid_argument("--role '" + flag + "' is not ROLE=VENDOR:PRODUCT[:SERIAL]");
            DeviceRole r{flag.substr(0, eq), resolve(flag.substr(eq + 1), adapters, sysfs)};
            check_role_name(r.role);
            changes.push_back(std::move(r));
        }
        roles = merge_roles(std::move(roles), changes);
        const std::string text = format_roles(roles);
        if (print) {
            std::cout << text;
            return 0;
        }
        std::string why;
        if (!ugv::io::write_file_atomically(config, text.data(), text.size(), why)) {
            std::cerr << "ugv-udev-setup: " << why << "\n";
            return 2;
        }
        std::cout << "wrote " << config << ": " << roles.size() << " role(s)\n";
        for (const auto& r : roles) std::cout << "  /dev/ugv/" << r.role << "  " << format_usb_id(r.id) << "\n";
        // udev reads the roles when an adapter appears: replay the events of the attached ones.
        const char* trigger = "udevadm trigger --action=add --subsystem-match=usb-serial --subsystem-match=tty";
        if (!no_trigger && config == kDefaultConfig && ::access("/run/udev/control", F_OK) == 0) {
            if (std::system(trigger) != 0) std::cerr << "ugv-udev-setup: '" << trigger << "' failed; replug the adapters\n";
        } else {
            std::cout << "apply to attached adapters: sudo " << trigger << "\n";
        }
        return 0;
    } catch (const ugv::runtime::ConfigError& e) {
        std::cerr << e.what() << "\n";
        return 2;
    } catch (const std::invalid_argument& e) {
        std::cerr << "ugv-udev-setup: " << e.what() << "\n";
        return 2;
    }
}
