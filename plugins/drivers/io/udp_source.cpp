// udp://HOST:PORT[?group=G]: datagrams received without blocking, one entry each, never split.
#include "transports.hpp"

#include <sys/socket.h>
#include <sys/uio.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <optional>
#include <utility>

namespace brickyard::drivers {
namespace {

// IPv4's largest UDP payload is 65,507 bytes: a buffer of 64 KiB never cuts one.
constexpr size_t kMaxDatagram = 64 * 1024;
// An Ouster sensor sends some 30 MB/s; at a 100 Hz step that is 300 KB between polls, over
// Linux's default 208 KiB receive buffer. The kernel caps the request at net.core.rmem_max.
constexpr int kReceiveBuffer = 8 * 1024 * 1024;

class UdpSource final : public ByteSource {
 public:
  UdpSource(UniqueFd fd, std::string name) : fd_(std::move(fd)), name_(std::move(name)), scratch_(kMaxDatagram) {}

  bool poll(std::vector<std::vector<uint8_t>>& out, size_t max_bytes) override {
    arrivals_.clear();
    if (!error_.empty()) return false;
    size_t total = 0;
    if (held_) {
      total += cost(held_->size());
      out.push_back(std::move(*held_));
      arrivals_.push_back(held_arrival_);
      held_.reset();
    }
    while (total < max_bytes) {
      int64_t arrival = -1;
      ssize_t n = receive(arrival);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
      if (n < 0) {
        error_ = device_error(name_, "receive failed", errno);
        fd_.reset();
        return false;
      }
      std::vector<uint8_t> datagram(scratch_.begin(), scratch_.begin() + n);
      // Past the bound it waits for the next poll; the first of a call always goes, so a
      // datagram larger than max_bytes is not stuck.
      if (total > 0 && total + cost(datagram.size()) > max_bytes) {
        held_ = std::move(datagram);
        held_arrival_ = arrival;
        return true;
      }
      total += cost(datagram.size());
      out.push_back(std::move(datagram));
      arrivals_.push_back(arrival);
    }
    return true;
  }

  const std::string& error() const override { return error_; }
  bool datagrams() const override { return true; }
  int fd() const override { return fd_.get(); }
  const std::vector<int64_t>& arrivals_ns() const override { return arrivals_; }

 private:
  // One datagram into scratch_, with the kernel's receive time (-1 where none came with it).
  ssize_t receive(int64_t& arrival) {
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timespec))];
    iovec io{scratch_.data(), scratch_.size()};
    msghdr m{};
    m.msg_iov = &io, m.msg_iovlen = 1;
    m.msg_control = control, m.msg_controllen = sizeof control;
    const ssize_t n = ::recvmsg(fd_.get(), &m, 0);
    if (n < 0) return n;
    for (cmsghdr* c = CMSG_FIRSTHDR(&m); c; c = CMSG_NXTHDR(&m, c))
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMPNS) {
        timespec t;
        std::memcpy(&t, CMSG_DATA(c), sizeof t);
        arrival = static_cast<int64_t>(t.tv_sec) * 1000000000 + t.tv_nsec;
      }
    return n;
  }

  // An empty datagram counts as one byte, so a flood of them still ends a poll.
  static size_t cost(size_t size) { return std::max<size_t>(size, 1); }

  UniqueFd fd_;
  std::string name_;
  std::vector<uint8_t> scratch_;
  std::optional<std::vector<uint8_t>> held_;  // read past the last poll's bound
  int64_t held_arrival_ = -1;
  std::vector<int64_t> arrivals_;  // of the last poll's entries
  std::string error_;
};

// Joins the group on the interface whose address is HOST (0.0.0.0: the one the routing table picks).
bool join_group(int fd, const SourceSpec& spec) {
  ip_mreq request{};
  sockaddr_in group{}, interface{};
  if (!ipv4_address(spec.group, 0, group) || !ipv4_address(spec.host, 0, interface)) {
    errno = EINVAL;
    return false;
  }
  request.imr_multiaddr = group.sin_addr;
  request.imr_interface = interface.sin_addr;
  return ::setsockopt(fd, IPPROTO_IP, IP_ADD_MEMBERSHIP, &request, sizeof request) == 0;
}

}  // namespace

std::unique_ptr<ByteSource> open_udp_source(const SourceSpec& spec, const std::string& name, std::string& error) {
  // With a group, the socket is bound to the group's address: bound to HOST's, Linux would
  // deliver only datagrams sent to HOST itself. HOST then names the interface to join on.
  const std::string& bind_host = spec.group.empty() ? spec.host : spec.group;
  sockaddr_in address{};
  if (!ipv4_address(bind_host, spec.port, address)) {
    error = device_error(name, "'" + bind_host + "' is not an IPv4 address", 0);
    return nullptr;
  }
  UniqueFd fd = ipv4_socket(SOCK_DGRAM);
  if (!fd.valid()) {
    error = device_error(name, "cannot create a socket", errno);
    return nullptr;
  }
  // SO_REUSEADDR: a driver restarted at once binds again (and several may share a multicast port).
  int on = 1;
  ::setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  ::setsockopt(fd.get(), SOL_SOCKET, SO_RCVBUF, &kReceiveBuffer, sizeof kReceiveBuffer);
  // Each datagram's receive time from the kernel: what the driver's own latency is measured from.
  ::setsockopt(fd.get(), SOL_SOCKET, SO_TIMESTAMPNS, &on, sizeof on);
  if (::bind(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    error = device_error(name, "cannot bind " + bind_host + ":" + std::to_string(spec.port), errno);
    return nullptr;
  }
  if (!spec.group.empty() && !join_group(fd.get(), spec)) {
    error = device_error(name, "cannot join group " + spec.group + " on " + spec.host, errno);
    return nullptr;
  }
  return std::make_unique<UdpSource>(std::move(fd), name);
}

}  // namespace brickyard::drivers
