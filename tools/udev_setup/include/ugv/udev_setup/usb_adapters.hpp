// The USB serial adapters attached now, read from sysfs (a fake tree in tests).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "ugv/udev_setup/device_roles.hpp"

namespace ugv::udev_setup {

struct SerialAdapter
{
    std::string tty;           // ttyUSB0, ttyACM0
    UsbId id;                  // serial as udev's ID_SERIAL_SHORT has it
    std::string driver;        // ftdi_sio, pl2303, cdc_acm, ...
    std::string manufacturer;  // the USB device's strings, when it has them
    std::string product;
    std::string usb_port;      // the USB device's sysfs name, e.g. 1-1.2 (which socket)
};

// Every tty under SYSFS/class/tty whose device sits on a USB device, by tty name.
// Entries that are not USB or whose ids cannot be read are left out.
std::vector<SerialAdapter> list_serial_adapters(const std::filesystem::path& sysfs);

// "ttyUSB0  0403:6001:A50285BI  ftdi_sio  FTDI FT232R USB UART  (USB 1-1.2)"
std::string describe(const SerialAdapter& a);

}  // namespace ugv::udev_setup
