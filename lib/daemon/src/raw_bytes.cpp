#include "ugv/daemon/raw_bytes.hpp"

namespace ugv::daemon {

raw_bytes_t raw_bytes_message(const std::string& device, bool to_device, const uint8_t* data, std::size_t n,
                              int64_t utime, int64_t seq)
{
    raw_bytes_t m{};
    m.utime = utime;
    m.seq = seq;
    m.device = device;
    m.direction = to_device ? raw_bytes_t::DIRECTION_TO_DEVICE : raw_bytes_t::DIRECTION_FROM_DEVICE;
    m.nbytes = static_cast<int32_t>(n);
    m.data.assign(data, data + n);
    return m;
}

}  // namespace ugv::daemon
