// udp://HOST:PORT[?group=G]: datagrams received without blocking, one entry each, never split.
#include "transports.hpp"

#include <sys/socket.h>

#include <algorithm>
#include <cerrno>
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
    if (!error_.empty()) return false;
    size_t total = 0;
    if (held_) {
      total += cost(held_->size());
      out.push_back(std::move(*held_));
      held_.reset();
    }
    while (total < max_bytes) {
      ssize_t n = ::recv(fd_.get(), scratch_.data(), scratch_.size(), 0);
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
        return true;
      }
      total += cost(datagram.size());
      out.push_back(std::move(datagram));
    }
    return true;
  }

  const std::string& error() const override { return error_; }
  bool datagrams() const override { return true; }

 private:
  // An empty datagram counts as one byte, so a flood of them still ends a poll.
  static size_t cost(size_t size) { return std::max<size_t>(size, 1); }

  UniqueFd fd_;
  std::string name_;
  std::vector<uint8_t> scratch_;
  std::optional<std::vector<uint8_t>> held_;  // read past the last poll's bound
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
