// tcp://HOST:PORT as a source: a client of a receiver's port (a NovAtel ICOM port), read as a stream.
#include "transports.hpp"

#include <sys/socket.h>

#include <cerrno>

namespace brickyard::drivers {

// The connect is started, not waited for: a receiver that does not answer would hold the start
// for minutes of SYN retries. A refusal known at once fails the open; one learnt later is the
// first poll's error ("connection failed: Connection refused").
std::unique_ptr<ByteSource> open_tcp_source(const SourceSpec& spec, const std::string& name, std::string& error) {
  sockaddr_in address{};
  UniqueFd fd = ipv4_socket_for(spec.host, spec.port, SOCK_STREAM, name, address, error);
  if (!fd.valid()) return nullptr;
  int rc = ::connect(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address);
  if (rc != 0 && errno != EINPROGRESS && errno != EINTR) {
    error = device_error(name, "cannot connect", errno);
    return nullptr;
  }
  return make_stream_source(std::move(fd), name, {"closed by the peer", "connection failed"});
}

}  // namespace brickyard::drivers
