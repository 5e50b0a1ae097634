#include "socketcan_transport.hpp"

#include <cerrno>
#include <cstring>
#include <linux/can.h>
#include <linux/can/error.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include "ugv/io/clock.hpp"

namespace ugv::io {

bool socketcan_available()
{
    const int s = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (s < 0) return false;
    ::close(s);
    return true;
}

SocketCanTransport::SocketCanTransport(std::string interface) : interface_(std::move(interface)) {}

SocketCanTransport::~SocketCanTransport() { close(); }

bool SocketCanTransport::open()
{
    close();
    fd_ = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC | SOCK_NONBLOCK, CAN_RAW);
    if (fd_ < 0) {
        error_ = describe() + ": cannot create a CAN socket: " + std::strerror(errno);
        return false;
    }
    ifreq ifr{};
    std::strncpy(ifr.ifr_name, interface_.c_str(), IFNAMSIZ - 1);
    if (ioctl(fd_, SIOCGIFINDEX, &ifr) != 0) {
        error_ = describe() + ": no such interface: " + std::strerror(errno);
        close();
        return false;
    }
    // Bus-off, controller problems and lost arbitration arrive as error frames.
    can_err_mask_t mask = CAN_ERR_MASK;
    setsockopt(fd_, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &mask, sizeof mask);
    int on = 1;
    setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMP, &on, sizeof on);
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifr.ifr_ifindex;
    if (::bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        error_ = describe() + ": bind: " + std::strerror(errno);
        close();
        return false;
    }
    return true;
}

void SocketCanTransport::close()
{
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

bool SocketCanTransport::send(const CanFrame& f)
{
    can_frame raw{};
    raw.can_id = f.id | (f.extended ? CAN_EFF_FLAG : 0u) | (f.rtr ? CAN_RTR_FLAG : 0u);
    raw.can_dlc = f.dlc > 8 ? 8 : f.dlc;
    std::memcpy(raw.data, f.data.data(), raw.can_dlc);
    if (::write(fd_, &raw, sizeof raw) != static_cast<ssize_t>(sizeof raw)) {
        error_ = describe() + ": send: " + std::strerror(errno);
        return false;
    }
    return true;
}

CanReceive SocketCanTransport::receive(int timeout_ms)
{
    CanReceive r;
    if (fd_ < 0) {
        r.status = CanReceive::Status::closed;
        return r;
    }
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) <= 0) return r;
    can_frame raw{};
    char control[CMSG_SPACE(sizeof(timeval))];
    iovec iov{&raw, sizeof raw};
    msghdr msg{};
    msg.msg_iov = &iov;
    msg.msg_iovlen = 1;
    msg.msg_control = control;
    msg.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(fd_, &msg, 0);
    r.utime = now_utime();
    if (n < 0) {
        r.status = errno == ENETDOWN || errno == ENODEV ? CanReceive::Status::closed : CanReceive::Status::error;
        r.detail = std::strerror(errno);
        return r;
    }
    for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c)) {
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SO_TIMESTAMP) {
            timeval tv{};
            std::memcpy(&tv, CMSG_DATA(c), sizeof tv);
            r.utime = static_cast<int64_t>(tv.tv_sec) * 1'000'000 + tv.tv_usec;
        }
    }
    if (raw.can_id & CAN_ERR_FLAG) {
        r.status = CanReceive::Status::bus_error;
        r.detail = (raw.can_id & CAN_ERR_BUSOFF) ? "bus-off" : "CAN error frame";
        return r;
    }
    r.status = CanReceive::Status::frame;
    r.frame.extended = (raw.can_id & CAN_EFF_FLAG) != 0;
    r.frame.rtr = (raw.can_id & CAN_RTR_FLAG) != 0;
    r.frame.id = raw.can_id & (r.frame.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
    r.frame.dlc = raw.can_dlc > 8 ? 8 : raw.can_dlc;
    std::memcpy(r.frame.data.data(), raw.data, r.frame.dlc);
    return r;
}

}  // namespace ugv::io
