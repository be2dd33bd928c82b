// IPv4 sockets as every network transport opens them: non-blocking (nothing may wait in a
// plugin's step) and close-on-exec (a child the host starts must not inherit a sensor's socket).
#include "transports.hpp"

#include <arpa/inet.h>
#include <sys/socket.h>

namespace brickyard::drivers {

bool ipv4_address(const std::string& host, uint16_t port, sockaddr_in& address) {
  address = sockaddr_in{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  return ::inet_pton(AF_INET, host.c_str(), &address.sin_addr) == 1;
}

UniqueFd ipv4_socket(int type) { return UniqueFd(::socket(AF_INET, type | SOCK_NONBLOCK | SOCK_CLOEXEC, 0)); }

}  // namespace brickyard::drivers
