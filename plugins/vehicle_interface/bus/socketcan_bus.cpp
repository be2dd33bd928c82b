// can://IFNAME: a SocketCAN raw socket on the car's interface (Linux's linux/can.h and
// linux/can/raw.h), non-blocking, CAN FD frames accepted when the interface carries them.
// Not exercised by the tests (these machines have no vcan): opening an interface that does not
// exist is (bad_input.raptor_dbw_no_can_interface).
#include "can_bus.hpp"

#include "drivers/io/fd.hpp"

#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace brickyard::vehicle_interface {

namespace {

CanFrame from_kernel(const canfd_frame& k, bool fd) {
  CanFrame f;
  f.extended = (k.can_id & CAN_EFF_FLAG) != 0;
  f.remote = !fd && (k.can_id & CAN_RTR_FLAG) != 0;
  f.id = k.can_id & (f.extended ? CAN_EFF_MASK : CAN_SFF_MASK);
  f.fd = fd;
  f.fd_flags = fd ? k.flags : 0;
  f.length = static_cast<uint8_t>(std::min<size_t>(k.len, fd ? CANFD_MAX_DLEN : CAN_MAX_DLEN));
  if (!f.remote) std::memcpy(f.data.data(), k.data, f.length);
  return f;
}

canfd_frame to_kernel(const CanFrame& f) {
  canfd_frame k{};
  k.can_id = f.id | (f.extended ? CAN_EFF_FLAG : 0u) | (f.remote ? CAN_RTR_FLAG : 0u);
  k.len = f.length;
  k.flags = f.fd ? f.fd_flags : 0;
  if (!f.remote) std::memcpy(k.data, f.data.data(), f.length);
  return k;
}

class SocketCanBus final : public CanBus {
 public:
  SocketCanBus(drivers::UniqueFd fd, std::string name) : fd_(std::move(fd)), name_(std::move(name)) {}

  bool poll(std::vector<CanFrame>& out, size_t max_frames) override {
    if (!error_.empty()) return false;
    for (size_t n = 0; n < max_frames; ++n) {
      canfd_frame k{};
      const ssize_t got = ::read(fd_.get(), &k, sizeof k);
      if (got < 0 && errno == EINTR) continue;
      if (got < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return true;
      if (got < 0) return fail("receive failed", errno);
      if (got != CAN_MTU && got != CANFD_MTU) continue;  // no frame the kernel sends
      if (k.can_id & CAN_ERR_FLAG) {
        ++counts_.error_frames;
        continue;
      }
      out.push_back(from_kernel(k, got == CANFD_MTU));
      ++counts_.frames_in;
    }
    return true;
  }

  bool send(const std::vector<CanFrame>& frames) override {
    if (!error_.empty()) return false;
    for (const CanFrame& f : frames) {
      const canfd_frame k = to_kernel(f);
      const size_t size = f.fd ? CANFD_MTU : CAN_MTU;
      ssize_t n;
      do n = ::write(fd_.get(), &k, size);
      while (n < 0 && errno == EINTR);
      if (n == static_cast<ssize_t>(size)) {
        ++counts_.frames_out;
      } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == ENOBUFS)) {
        ++counts_.frames_dropped;  // the interface's queue is full: lost, as on a busy bus
      } else {
        return fail("send failed", n < 0 ? errno : EIO);
      }
    }
    return true;
  }

  const std::string& error() const override { return error_; }
  const BusCounts& counts() const override { return counts_; }

 private:
  bool fail(const char* what, int err) {
    error_ = drivers::device_error(name_, what, err);
    fd_.reset();
    return false;
  }

  drivers::UniqueFd fd_;
  std::string name_;
  BusCounts counts_;
  std::string error_;
};

}  // namespace

std::unique_ptr<CanBus> open_socketcan_bus(const BusSpec& spec, std::string& error) {
  const unsigned index = ::if_nametoindex(spec.interface.c_str());
  if (index == 0) {
    error = spec.text + ": no such network interface (ip link shows the CAN interfaces)";
    return nullptr;
  }
  drivers::UniqueFd fd(::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW));
  if (!fd.valid()) {
    error = drivers::device_error(spec.text, "cannot open a CAN socket", errno);
    return nullptr;
  }
  const int on = 1;  // CAN FD frames too, where the interface carries them (refused on old kernels: classic only)
  (void)::setsockopt(fd.get(), SOL_CAN_RAW, CAN_RAW_FD_FRAMES, &on, sizeof on);
  sockaddr_can address{};
  address.can_family = AF_CAN;
  address.can_ifindex = static_cast<int>(index);
  if (::bind(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    error = drivers::device_error(spec.text, "cannot bind (is it a CAN interface, and up?)", errno);
    return nullptr;
  }
  return std::make_unique<SocketCanBus>(std::move(fd), spec.text);
}

}  // namespace brickyard::vehicle_interface
