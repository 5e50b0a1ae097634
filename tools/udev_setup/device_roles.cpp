#include "ugv/udev_setup/device_roles.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

#include "ugv/runtime/config.hpp"

namespace ugv::udev_setup {

namespace {

bool is_hex4(const std::string& s)
{
    return s.size() == 4 && std::all_of(s.begin(), s.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; });
}

std::string lower(std::string s)
{
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool same_adapter(const UsbId& a, const UsbId& b)
{
    return a.vendor == b.vendor && a.product == b.product && a.serial == b.serial;
}

// Throws std::invalid_argument naming both roles when two entries name one adapter.
void check_distinct(const std::vector<DeviceRole>& roles)
{
    for (std::size_t i = 0; i < roles.size(); ++i)
        for (std::size_t j = i + 1; j < roles.size(); ++j)
            if (same_adapter(roles[i].id, roles[j].id))
                throw std::invalid_argument("roles '" + roles[i].role + "' and '" + roles[j].role + "' name the same adapter " +
                                            format_usb_id(roles[i].id));
}

}  // namespace

void check_role_name(const std::string& role)
{
    if (role.empty()) throw std::invalid_argument("empty role name");
    if (role.size() > 64) throw std::invalid_argument("role name '" + role + "' is longer than 64 characters");
    if (!std::isalnum(static_cast<unsigned char>(role[0])))
        throw std::invalid_argument("role name '" + role + "' must start with a letter or digit");
    for (const char c : role)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.')
            throw std::invalid_argument("role name '" + role + "' may hold only letters, digits, '-', '_' and '.'");
}

UsbId parse_usb_id(const std::string& text)
{
    const auto c1 = text.find(':');
    if (c1 == std::string::npos)
        throw std::invalid_argument("'" + text + "' is not VENDOR:PRODUCT[:SERIAL] (e.g. 0403:6001:A50285BI)");
    const auto c2 = text.find(':', c1 + 1);
    UsbId id;
    id.vendor = text.substr(0, c1);
    id.product = text.substr(c1 + 1, c2 == std::string::npos ? std::string::npos : c2 - c1 - 1);
    if (c2 != std::string::npos) id.serial = text.substr(c2 + 1);
    if (!is_hex4(id.vendor)) throw std::invalid_argument("vendor '" + id.vendor + "' in '" + text + "' is not 4 hex digits");
    if (!is_hex4(id.product)) throw std::invalid_argument("product '" + id.product + "' in '" + text + "' is not 4 hex digits");
    id.vendor = lower(id.vendor);
    id.product = lower(id.product);
    if (c2 != std::string::npos && id.serial.empty())
        throw std::invalid_argument("empty serial in '" + text + "' (leave out the last ':' to match any serial)");
    if (udev_serial(id.serial) != id.serial)
        throw std::invalid_argument("serial '" + id.serial + "' has characters udev replaces; as udev sees it: '" +
                                    udev_serial(id.serial) + "'");
    return id;
}

DeviceRole parse_role_flag(const std::string& text)
{
    const auto eq = text.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("'" + text + "' is not ROLE=VENDOR:PRODUCT[:SERIAL]");
    DeviceRole r{text.substr(0, eq), parse_usb_id(text.substr(eq + 1))};
    check_role_name(r.role);
    return r;
}

std::string format_usb_id(const UsbId& id)
{
    return id.vendor + ":" + id.product + (id.serial.empty() ? "" : ":" + id.serial);
}

std::string udev_serial(const std::string& raw)
{
    const auto first = raw.find_first_not_of(" \t\n\r\f\v");
    if (first == std::string::npos) return {};
    const auto last = raw.find_last_not_of(" \t\n\r\f\v");
    std::string out;
    bool in_space = false;
    for (std::size_t i = first; i <= last; ++i) {
        const auto u = static_cast<unsigned char>(raw[i]);
        if (std::isspace(u)) {
            if (!in_space) out += '_';
            in_space = true;
            continue;
        }
        in_space = false;
        const bool keep = u < 0x80 && (std::isalnum(u) || std::string_view("#+-.:=@_").find(static_cast<char>(u)) != std::string_view::npos);
        out += keep ? static_cast<char>(u) : '_';
    }
    return out;
}

std::vector<DeviceRole> parse_roles(const std::string& text, const std::string& name)
{
    std::vector<DeviceRole> roles;
    std::istringstream in(text);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const std::string where = "line " + std::to_string(n);
        if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
        std::istringstream words(line);
        std::string role, id, extra;
        if (!(words >> role)) continue;
        if (!(words >> id)) throw runtime::ConfigError(name, where, "'" + role + "' has no VENDOR:PRODUCT[:SERIAL]");
        if (words >> extra) throw runtime::ConfigError(name, where, "unexpected '" + extra + "' after the adapter");
        try {
            check_role_name(role);
            DeviceRole r{role, parse_usb_id(id)};
            for (const auto& other : roles)
                if (other.role == role) throw std::invalid_argument("role '" + role + "' is given twice");
            roles.push_back(std::move(r));
            check_distinct(roles);
        } catch (const std::invalid_argument& e) {
            throw runtime::ConfigError(name, where, e.what());
        }
    }
    return roles;
}

std::string format_roles(const std::vector<DeviceRole>& roles)
{
    std::string out =
        "# USB serial adapters udev names /dev/ugv/<role> (/lib/udev/rules.d/60-ugv.rules).\n"
        "# Written by ugv-udev-setup; one adapter a line: ROLE VENDOR:PRODUCT[:SERIAL]\n"
        "# (no serial: any adapter of that vendor and product).\n";
    for (const auto& r : roles) out += r.role + " " + format_usb_id(r.id) + "\n";
    return out;
}

std::vector<DeviceRole> merge_roles(std::vector<DeviceRole> roles, const std::vector<DeviceRole>& changes)
{
    for (const auto& c : changes) {
        auto it = std::find_if(roles.begin(), roles.end(), [&](const DeviceRole& r) { return r.role == c.role; });
        if (it != roles.end()) it->id = c.id;
        else roles.push_back(c);
    }
    check_distinct(roles);
    return roles;
}

std::optional<std::string> lookup_role(const std::vector<DeviceRole>& roles, const UsbId& adapter)
{
    const auto vendor = lower(adapter.vendor), product = lower(adapter.product);
    const DeviceRole* any_serial = nullptr;
    for (const auto& r : roles) {
        if (r.id.vendor != vendor || r.id.product != product) continue;
        if (!r.id.serial.empty() && r.id.serial == adapter.serial) return r.role;
        if (r.id.serial.empty() && any_serial == nullptr) any_serial = &r;
    }
    if (any_serial != nullptr) return any_serial->role;
    return std::nullopt;
}

}  // namespace ugv::udev_setup
