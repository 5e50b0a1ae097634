#include "ugv/sick_lms2xx/requests.hpp"

#include <stdexcept>

#include "ugv/sick_lms2xx/telegram.hpp"

namespace ugv::sick_lms2xx {

std::optional<uint8_t> baud_mode_byte(int baud)
{
    switch (baud) {
    case 9600: return kModeBaud9600;
    case 19200: return kModeBaud19200;
    case 38400: return kModeBaud38400;
    case 500000: return kModeBaud500000;
    default: return std::nullopt;
    }
}

static std::vector<uint8_t> mode_request(uint8_t mode)
{
    const uint8_t data[] = {mode};
    return encode_request(cmd::switch_mode, data);
}

std::vector<uint8_t> request_baud(int baud)
{
    const auto mode = baud_mode_byte(baud);
    if (!mode) throw std::invalid_argument("sick_lms2xx: unsupported baud rate " + std::to_string(baud));
    return mode_request(*mode);
}

std::vector<uint8_t> request_installation_mode(const std::string& password)
{
    std::vector<uint8_t> data{kModeInstallation};
    data.insert(data.end(), password.begin(), password.end());
    return encode_request(cmd::switch_mode, data);
}

std::vector<uint8_t> request_start_streaming() { return mode_request(kModeStreamAll); }
std::vector<uint8_t> request_stop_streaming() { return mode_request(kModeRequest); }
std::vector<uint8_t> request_type() { return encode_request(cmd::type); }
std::vector<uint8_t> request_status() { return encode_request(cmd::status); }

std::vector<uint8_t> request_variant(int angle_deg, int resolution_cdeg)
{
    if (angle_deg != 100 && angle_deg != 180) throw std::invalid_argument("sick_lms2xx: variant angle must be 100 or 180");
    if (resolution_cdeg != 25 && resolution_cdeg != 50 && resolution_cdeg != 100)
        throw std::invalid_argument("sick_lms2xx: variant resolution must be 25, 50 or 100 (0.01 deg)");
    std::vector<uint8_t> data;
    put_u16le(data, static_cast<uint16_t>(angle_deg));
    put_u16le(data, static_cast<uint16_t>(resolution_cdeg));
    return encode_request(cmd::variant, data);
}

std::vector<uint8_t> request_read_config() { return encode_request(cmd::read_config); }
std::vector<uint8_t> request_write_config(std::span<const uint8_t> block) { return encode_request(cmd::write_config, block); }
std::vector<uint8_t> request_reset() { return encode_request(cmd::reset); }

}  // namespace ugv::sick_lms2xx
