#include <cstdlib>

#include "ugv/bus/bus.hpp"

namespace ugv::bus {

std::string default_url()
{
    const char* env = std::getenv("LCM_DEFAULT_URL");
    return env && *env ? env : "udpm://239.255.76.67:7667?ttl=0";
}

}  // namespace ugv::bus
