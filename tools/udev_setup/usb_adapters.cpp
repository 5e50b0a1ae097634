#include "ugv/udev_setup/usb_adapters.hpp"

#include <algorithm>
#include <fstream>
#include <system_error>

namespace ugv::udev_setup {

namespace fs = std::filesystem;

namespace {

// A sysfs attribute's first line, or empty when it cannot be read.
std::string attribute(const fs::path& dir, const char* name)
{
    std::ifstream in(dir / name);
    std::string line;
    if (in) std::getline(in, line);
    return line;
}

}  // namespace

std::vector<SerialAdapter> list_serial_adapters(const fs::path& sysfs)
{
    std::vector<SerialAdapter> out;
    std::error_code ec;
    const fs::path root = fs::weakly_canonical(sysfs, ec);
    for (const auto& entry : fs::directory_iterator(sysfs / "class" / "tty", ec)) {
        std::error_code e;
        const fs::path device = fs::canonical(entry.path() / "device", e);
        if (e) continue;  // a virtual tty (console, ptmx, ttyN)
        // Up from the tty's device (usb-serial port or USB interface) to the USB device.
        fs::path usb = device;
        while (usb != root && usb.has_relative_path() && !fs::exists(usb / "idVendor", e)) usb = usb.parent_path();
        if (usb == root || !fs::exists(usb / "idVendor", e)) continue;
        SerialAdapter a;
        a.tty = entry.path().filename().string();
        a.id.vendor = attribute(usb, "idVendor");
        a.id.product = attribute(usb, "idProduct");
        a.id.serial = udev_serial(attribute(usb, "serial"));
        try {
            a.id = parse_usb_id(format_usb_id(a.id));
        } catch (const std::invalid_argument&) {
            continue;
        }
        const fs::path driver = fs::canonical(device / "driver", e);
        if (!e) a.driver = driver.filename().string();
        a.manufacturer = attribute(usb, "manufacturer");
        a.product = attribute(usb, "product");
        a.usb_port = usb.filename().string();
        out.push_back(std::move(a));
    }
    std::sort(out.begin(), out.end(), [](const SerialAdapter& x, const SerialAdapter& y) { return x.tty < y.tty; });
    return out;
}

std::string describe(const SerialAdapter& a)
{
    std::string s = a.tty + "  " + format_usb_id(a.id) + "  " + (a.driver.empty() ? "-" : a.driver);
    const std::string name = a.manufacturer + (a.manufacturer.empty() || a.product.empty() ? "" : " ") + a.product;
    if (!name.empty()) s += "  " + name;
    return s + "  (USB " + a.usb_port + ")";
}

}  // namespace ugv::udev_setup
