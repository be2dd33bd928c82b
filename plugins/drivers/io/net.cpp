// IPv4 sockets as every network transport opens them: non-blocking (nothing may wait in a
// plugin's step) and close-on-exec (a child the host starts must not inherit a sensor's socket).
#include "transports.hpp"

#include <arpa/inet.h>
#include <cerrno>
#include <sys/socket.h>

namespace brickyard::drivers {

bool ipv4_address(const std::string& host, uint16_t port, sockaddr_in& address) {
  address = sockaddr_in{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  return ::inet_pton(AF_INET, host.c_str(), &address.sin_addr) == 1;
}

UniqueFd ipv4_socket(int type) { return UniqueFd(::socket(AF_INET, type | SOCK_NONBLOCK | SOCK_CLOEXEC, 0)); }

UniqueFd ipv4_socket_for(const std::string& host, uint16_t port, int type, const std::string& name, sockaddr_in& address,
                         std::string& error) {
  if (!ipv4_address(host, port, address)) {
    error = device_error(name, "'" + host + "' is not an IPv4 address", 0);
    return UniqueFd();
  }
  UniqueFd fd = ipv4_socket(type);
  if (!fd.valid()) error = device_error(name, "cannot create a socket", errno);
  return fd;
}

}  // namespace brickyard::drivers
