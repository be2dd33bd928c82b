// A pseudo-terminal pair, so a serial:// driver can be tested, and run against the simulator,
// with no port: the simulator writes the master, the driver opens the slave's path.
#include "transports.hpp"

#include <fcntl.h>
#include <stdlib.h>
#include <termios.h>

#include <cerrno>

namespace brickyard::drivers {

std::optional<Pty> open_pty(std::string& error) {
  UniqueFd master(::posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC));
  if (!master.valid()) {
    error = device_error("pty", "cannot open a pseudo-terminal", errno);
    return std::nullopt;
  }
  if (::grantpt(master.get()) != 0 || ::unlockpt(master.get()) != 0) {
    error = device_error("pty", "cannot unlock its slave", errno);
    return std::nullopt;
  }
  char path[128];
  if (int err = ::ptsname_r(master.get(), path, sizeof path); err != 0) {  // returns the error, not errno
    error = device_error("pty", "cannot name its slave", err);
    return std::nullopt;
  }
  // On Linux the master's termios calls act on the slave: raw here means no echo of what the
  // simulator writes and no translation of line ends, before any driver opens the slave.
  termios tio{};
  if (::tcgetattr(master.get(), &tio) != 0) {
    error = device_error("pty", "cannot read its settings", errno);
    return std::nullopt;
  }
  ::cfmakeraw(&tio);
  if (::tcsetattr(master.get(), TCSANOW, &tio) != 0) {
    error = device_error("pty", "cannot make it raw", errno);
    return std::nullopt;
  }
  Pty pty;
  pty.slave_path = path;
  pty.master_fd = master.release();  // the caller's now
  return pty;
}

std::unique_ptr<ByteSink> pty_sink(const Pty& pty) {
  return make_fd_sink(UniqueFd(pty.master_fd), "pty master of " + pty.slave_path);
}

}  // namespace brickyard::drivers
