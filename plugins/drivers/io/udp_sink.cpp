// udp://HOST:PORT as a sink: each send one datagram to HOST:PORT (or to the group, with ?group=).
#include "transports.hpp"

#include <sys/socket.h>

#include <cerrno>
#include <utility>

namespace brickyard::drivers {
namespace {

class UdpSink final : public ByteSink {
 public:
  UdpSink(UniqueFd fd, std::string name, sockaddr_in to) : fd_(std::move(fd)), name_(std::move(name)), to_(to) {}

  bool send(const uint8_t* data, size_t size) override {
    if (!error_.empty()) return false;
    for (;;) {
      ssize_t n = ::sendto(fd_.get(), data, size, MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(&to_), sizeof to_);
      if (n >= 0) return true;
      if (errno == EINTR) continue;
      // A full send buffer, or an earlier datagram's ICMP "port unreachable" (no driver
      // listening yet): the datagram is lost, as on a wire, and the sink goes on.
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS || errno == ECONNREFUSED) {
        dropped_ += size;
        return true;
      }
      error_ = device_error(name_, "send failed", errno);
      return false;
    }
  }

  const std::string& error() const override { return error_; }
  uint64_t dropped() const override { return dropped_; }

 private:
  UniqueFd fd_;
  std::string name_;
  sockaddr_in to_;
  std::string error_;
  uint64_t dropped_ = 0;
};

// Multicast leaves by HOST's interface (0.0.0.0: the routing table's) with a TTL of 1, so no
// router forwards it past the link.
bool set_multicast(int fd, const sockaddr_in& interface) {
  unsigned char ttl = 1;
  return ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_IF, &interface.sin_addr, sizeof interface.sin_addr) == 0 &&
         ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl) == 0;
}

}  // namespace

std::unique_ptr<ByteSink> open_udp_sink(const SourceSpec& spec, const std::string& name, std::string& error) {
  const std::string& to_host = spec.group.empty() ? spec.host : spec.group;
  sockaddr_in to{}, interface{};
  bool to_ok = ipv4_address(to_host, spec.port, to);
  if (!to_ok || !ipv4_address(spec.host, 0, interface)) {
    error = device_error(name, "'" + (to_ok ? spec.host : to_host) + "' is not an IPv4 address", 0);
    return nullptr;
  }
  UniqueFd fd = ipv4_socket(SOCK_DGRAM);
  if (!fd.valid()) {
    error = device_error(name, "cannot create a socket", errno);
    return nullptr;
  }
  if (!spec.group.empty() && !set_multicast(fd.get(), interface)) {
    error = device_error(name, "cannot send to group " + spec.group + " on " + spec.host, errno);
    return nullptr;
  }
  return std::make_unique<UdpSink>(std::move(fd), name, to);
}

}  // namespace brickyard::drivers
