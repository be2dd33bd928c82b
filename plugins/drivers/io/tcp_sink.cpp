// tcp://HOST:PORT as a sink: listens on HOST:PORT, as a receiver's ICOM port does, and sends each
// message to every client connected, accepting new ones (without waiting) on each send.
#include "transports.hpp"

#include <sys/socket.h>

#include <cerrno>
#include <utility>
#include <vector>

namespace brickyard::drivers {
namespace {

// A receiver serves a few clients; the bound keeps one send's work bounded too.
constexpr size_t kMaxClients = 16;

class TcpSink final : public ByteSink {
 public:
  TcpSink(UniqueFd listener, std::string name) : listener_(std::move(listener)), name_(std::move(name)) {}

  bool send(const uint8_t* data, size_t size) override {
    if (!error_.empty() || !accept_waiting()) return false;
    for (size_t i = 0; i < clients_.size();) {
      if (send_to(clients_[i].get(), data, size)) {
        ++i;
      } else {
        clients_.erase(clients_.begin() + static_cast<std::ptrdiff_t>(i));  // it left; the rest go on
      }
    }
    return true;
  }

  const std::string& error() const override { return error_; }
  uint64_t dropped() const override { return dropped_; }

 private:
  bool accept_waiting() {
    while (clients_.size() < kMaxClients) {
      UniqueFd client(::accept4(listener_.get(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
      if (client.valid()) {
        clients_.push_back(std::move(client));
        continue;
      }
      if (errno == EINTR || errno == ECONNABORTED) continue;
      // Out of descriptors or memory: the client waits in the backlog for a later send.
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EMFILE || errno == ENFILE || errno == ENOBUFS ||
          errno == ENOMEM)
        return true;
      error_ = device_error(name_, "accept failed", errno);
      return false;
    }
    return true;
  }

  // False once the client has gone (reset, closed): it is dropped, the others still served.
  bool send_to(int fd, const uint8_t* data, size_t size) {
    size_t sent = 0;
    while (sent < size) {
      ssize_t n = ::send(fd, data + sent, size - sent, MSG_NOSIGNAL);
      if (n > 0) {
        sent += static_cast<size_t>(n);
        continue;
      }
      if (n < 0 && errno == EINTR) continue;
      if (n == 0 || errno == EAGAIN || errno == EWOULDBLOCK) break;  // a slow client loses the rest
      return false;
    }
    dropped_ += size - sent;
    return true;
  }

  UniqueFd listener_;
  std::string name_;
  std::vector<UniqueFd> clients_;
  std::string error_;
  uint64_t dropped_ = 0;
};

}  // namespace

std::unique_ptr<ByteSink> open_tcp_sink(const SourceSpec& spec, const std::string& name, std::string& error) {
  sockaddr_in address{};
  UniqueFd fd = ipv4_socket_for(spec.host, spec.port, SOCK_STREAM, name, address, error);
  if (!fd.valid()) return nullptr;
  int on = 1;  // a simulator restarted at once listens again despite the last run's TIME_WAIT
  ::setsockopt(fd.get(), SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
  if (::bind(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    error = device_error(name, "cannot bind " + spec.host + ":" + std::to_string(spec.port), errno);
    return nullptr;
  }
  if (::listen(fd.get(), static_cast<int>(kMaxClients)) != 0) {
    error = device_error(name, "cannot listen", errno);
    return nullptr;
  }
  return std::make_unique<TcpSink>(std::move(fd), name);
}

}  // namespace brickyard::drivers
