#include "ugv/bus/udpm_receiver.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <spdlog/spdlog.h>

#include "ugv/bus/bus.hpp"
#include "ugv/io/clock.hpp"

namespace ugv::bus::detail {
namespace {

constexpr std::size_t kBatch = 8;                // datagrams per recvmmsg()
constexpr std::size_t kDatagramBytes = 65536;    // the largest UDP payload
constexpr std::size_t kControlBytes = CMSG_SPACE(sizeof(timeval));

int64_t receive_time_us(msghdr& h)
{
    for (cmsghdr* c = CMSG_FIRSTHDR(&h); c; c = CMSG_NXTHDR(&h, c)) {
        if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMP) {
            timeval tv{};
            std::memcpy(&tv, CMSG_DATA(c), sizeof tv);
            return int64_t{tv.tv_sec} * 1'000'000 + tv.tv_usec;
        }
    }
    return io::now_utime();
}

}  // namespace

UdpmReceiver::UdpmReceiver(const UdpmUrl& url, ReassemblyLimits limits)
    : buffers_(kBatch * kDatagramBytes), control_(kBatch * kControlBytes), reassembler_(limits)
{
    const std::string where = "udpm " + url.group + ":" + std::to_string(url.port);
    in_addr group{};
    if (inet_pton(AF_INET, url.group.c_str(), &group) != 1 || !IN_MULTICAST(ntohl(group.s_addr)))
        throw BusError(where + ": '" + url.group + "' is not an IPv4 multicast address");
    fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd_ < 0) throw BusError(where + ": socket: " + std::strerror(errno));
    const auto fail = [&](const char* what) {
        const std::string why = where + ": " + what + ": " + std::strerror(errno);
        ::close(fd_);
        fd_ = -1;
        return BusError(why);
    };
    const int one = 1;
    // Every process on the host binds the same port, as liblcm's receivers do.
    if (::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one) != 0) throw fail("SO_REUSEADDR");
    if (::setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof one) != 0) throw fail("SO_TIMESTAMP");
    // The kernel buffer is all the queue there is between two drains (liblcm had a thread
    // and a 1 MB ring behind it): ask for 2 MiB unless the URL says otherwise. The kernel
    // caps the request at net.core.rmem_max, which the .deb raises (docs/deploy.md).
    const int want = url.recv_buf_size > 0 ? url.recv_buf_size : kDefaultReceiveBufferBytes;
    if (::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &want, sizeof want) != 0) throw fail("SO_RCVBUF");
    int granted = 0;
    socklen_t len = sizeof granted;
    if (::getsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &granted, &len) == 0) receive_buffer_bytes_ = granted / 2;
    if (receive_buffer_bytes_ < want)
        spdlog::warn("{}: receive buffer {} kB of {} kB asked (net.core.rmem_max); bursts of large messages "
                     "may be lost, see docs/deploy.md",
                     where, receive_buffer_bytes_ / 1024, want / 1024);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_ANY);
    addr.sin_port = htons(url.port);
    if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) throw fail("bind");
    ip_mreq membership{};
    membership.imr_multiaddr = group;
    membership.imr_interface.s_addr = htonl(INADDR_ANY);
    if (::setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &membership, sizeof membership) != 0)
        throw fail("joining the group (is there a multicast route? see docs/deploy.md)");
}

UdpmReceiver::~UdpmReceiver()
{
    if (fd_ >= 0) ::close(fd_);
}

DrainResult UdpmReceiver::drain(const Sink& sink, DrainBudget budget, const LcmReassembler::Wants* wants)
{
    DrainResult result;
    mmsghdr msgs[kBatch];
    iovec iov[kBatch];
    sockaddr_in from[kBatch];
    LcmReassembler::Message whole;
    // Unfinished messages age even while no fragment comes.
    reassembler_.expire(io::now_utime());
    std::size_t datagrams = 0, bytes = 0;
    for (;;) {
        if (datagrams >= budget.datagrams || bytes >= budget.bytes) {
            result.budget_spent = true;
            ++counters_.budget_stops;
            break;
        }
        const std::size_t want = std::min(kBatch, budget.datagrams - datagrams);
        for (std::size_t k = 0; k < want; ++k) {
            iov[k] = {buffers_.data() + k * kDatagramBytes, kDatagramBytes};
            msgs[k] = {};
            msgs[k].msg_hdr.msg_iov = &iov[k];
            msgs[k].msg_hdr.msg_iovlen = 1;
            msgs[k].msg_hdr.msg_name = &from[k];
            msgs[k].msg_hdr.msg_namelen = sizeof from[k];
            msgs[k].msg_hdr.msg_control = control_.data() + k * kControlBytes;
            msgs[k].msg_hdr.msg_controllen = kControlBytes;
        }
        const int n = ::recvmmsg(fd_, msgs, static_cast<unsigned>(want), MSG_DONTWAIT, nullptr);
        if (n <= 0) break;  // EAGAIN: all read (any other error: nothing to read either)
        for (int k = 0; k < n; ++k) {
            ++counters_.datagrams;
            ++datagrams;
            bytes += msgs[k].msg_len;
            const uint8_t* data = buffers_.data() + static_cast<std::size_t>(k) * kDatagramBytes;
            const LcmDatagram d = parse_lcm_datagram(data, msgs[k].msg_len);
            const int64_t recv_utime = receive_time_us(msgs[k].msg_hdr);
            if (d.kind == LcmDatagram::Kind::short_message) {
                ++counters_.messages;
                result.handed += sink(d.channel, d.payload, d.payload_size, recv_utime) ? 1 : 0;
                continue;
            }
            const uint64_t sender = (uint64_t{from[k].sin_addr.s_addr} << 16) | from[k].sin_port;
            if (!reassembler_.add_fragment(sender, d, recv_utime, whole, wants)) continue;
            ++counters_.messages;
            result.handed += sink(whole.channel, whole.payload.data(), whole.payload.size(), recv_utime) ? 1 : 0;
        }
        if (static_cast<std::size_t>(n) < want) break;
    }
    return result;
}

}  // namespace ugv::bus::detail
