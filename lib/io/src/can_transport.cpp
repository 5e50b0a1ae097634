#include "ugv/io/can_transport.hpp"

#include <stdexcept>

#include "slcan_transport.hpp"
#include "socketcan_transport.hpp"

namespace ugv::io {

std::unique_ptr<CanTransport> make_can_transport(const std::string& spec, int bitrate)
{
    const auto colon = spec.find(':');
    if (colon == std::string::npos || colon + 1 >= spec.size())
        throw std::invalid_argument("'" + spec + "' is not socketcan:IFACE or slcan:DEVICE[@BAUD]");
    const std::string kind = spec.substr(0, colon);
    const std::string rest = spec.substr(colon + 1);
    if (kind == "socketcan") return std::make_unique<SocketCanTransport>(rest);
    if (kind == "slcan") {
        const auto at = rest.rfind('@');
        int baud = 115200;
        std::string device = rest;
        if (at != std::string::npos) {
            device = rest.substr(0, at);
            try {
                std::size_t used = 0;
                baud = std::stoi(rest.substr(at + 1), &used);
                if (used != rest.size() - at - 1 || baud <= 0) throw std::invalid_argument("");
            } catch (const std::exception&) {
                throw std::invalid_argument("'" + rest.substr(at + 1) + "' is not a serial baud rate");
            }
        }
        if (device.empty()) throw std::invalid_argument("slcan needs a device path");
        return std::make_unique<SlcanTransport>(device, baud, bitrate);
    }
    throw std::invalid_argument("unknown CAN transport '" + kind + "' (socketcan or slcan)");
}

}  // namespace ugv::io
