// The device roles of /etc/ugv/devices.conf: which USB serial adapter (vendor, product,
// serial) udev names /dev/ugv/<role> (/lib/udev/rules.d/60-ugv.rules asks
// `ugv-udev-setup --lookup` for each adapter it sees).
//
// The file, one adapter a line, `#` starts a comment:
//   lms-front 0403:6001:FTLMS001
//   can-servo ad50:60c4           (no serial: any adapter of that vendor and product)
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace ugv::udev_setup {

struct UsbId
{
    std::string vendor;   // 4 lower-case hex digits
    std::string product;  // 4 lower-case hex digits
    std::string serial;   // as udev's ID_SERIAL_SHORT has it; empty = any serial
};

struct DeviceRole
{
    std::string role;  // the name under /dev/ugv/
    UsbId id;
};

// Throws std::invalid_argument with a one-line reason. A role becomes a file name under
// /dev/ugv: letters, digits, '-', '_' and '.', starting with a letter or digit, <= 64 chars.
void check_role_name(const std::string& role);
// "0403:6001:FTLMS001" or "0403:6001" (any serial); hex digits in either case.
UsbId parse_usb_id(const std::string& text);
// "ROLE=VENDOR:PRODUCT[:SERIAL]", the --role flag.
DeviceRole parse_role_flag(const std::string& text);
std::string format_usb_id(const UsbId& id);

// A serial number as udev's usb_id builtin puts it in ID_SERIAL_SHORT: surrounding
// whitespace dropped, inner whitespace runs and characters other than ASCII letters, digits
// and "#+-.:=@_" each replaced by '_'.
std::string udev_serial(const std::string& raw);

// Parses the file's text (name is used in errors). Throws runtime::ConfigError
// `NAME: line N: why` for a malformed line, a bad role name or id, a role given twice and
// two roles naming the same adapter.
std::vector<DeviceRole> parse_roles(const std::string& text, const std::string& name);
// The file's text: a header saying what it is, then one line a role, in the order given.
std::string format_roles(const std::vector<DeviceRole>& roles);
// roles with each of changes put in: a role already there is replaced in place, a new one
// appended. Throws std::invalid_argument if the result has two roles naming one adapter.
std::vector<DeviceRole> merge_roles(std::vector<DeviceRole> roles, const std::vector<DeviceRole>& changes);
// The role of the adapter vendor:product:serial. An entry with a serial wins over one
// without, so a spare adapter of the same kind does not take a configured one's name.
std::optional<std::string> lookup_role(const std::vector<DeviceRole>& roles, const UsbId& adapter);

}  // namespace ugv::udev_setup
