#include "serial_settings.hpp"

#include "fd.hpp"

#include <termios.h>

#include <array>
#include <cerrno>

namespace brickyard::drivers {
namespace {

struct Rate {
  int baud;
  speed_t speed;
};
// The POSIX B* rates and Linux's above 38400, up to 921600 (what GNSS receivers and USB serial
// adapters offer); B0 (hang up) is not a rate.
constexpr std::array<Rate, 22> kRates{{{50, B50},         {75, B75},         {110, B110},
                                       {134, B134},       {150, B150},       {200, B200},
                                       {300, B300},       {600, B600},       {1200, B1200},
                                       {1800, B1800},     {2400, B2400},     {4800, B4800},
                                       {9600, B9600},     {19200, B19200},   {38400, B38400},
                                       {57600, B57600},   {115200, B115200}, {230400, B230400},
                                       {460800, B460800}, {500000, B500000}, {576000, B576000},
                                       {921600, B921600}}};

struct Framing {
  std::string_view name;
  tcflag_t size;
  tcflag_t parity;  // PARENB, PARENB | PARODD, or 0
  tcflag_t stop;    // CSTOPB for two stop bits
};
constexpr std::array<Framing, 5> kFramings{{{"8N1", CS8, 0, 0},
                                            {"8E1", CS8, PARENB, 0},
                                            {"8O1", CS8, PARENB | PARODD, 0},
                                            {"7E1", CS7, PARENB, 0},
                                            {"8N2", CS8, 0, CSTOPB}}};

const Rate* find_rate(int baud) {
  for (const Rate& r : kRates)
    if (r.baud == baud) return &r;
  return nullptr;
}

const Framing* find_framing(std::string_view name) {
  for (const Framing& f : kFramings)
    if (f.name == name) return &f;
  return nullptr;
}

std::string failed(std::string_view what, int err) { return std::string(what) + ": " + os_error(err); }

}  // namespace

bool serial_baud_supported(int baud) { return find_rate(baud) != nullptr; }
bool serial_framing_supported(std::string_view framing) { return find_framing(framing) != nullptr; }

std::string serial_bauds_listed() {
  std::string text;
  for (const Rate& r : kRates) text += (text.empty() ? "" : ", ") + std::to_string(r.baud);
  return text;
}

std::string serial_framings_listed() {
  std::string text;
  for (const Framing& f : kFramings) text += (text.empty() ? "" : ", ") + std::string(f.name);
  return text;
}

std::string configure_serial(int fd, int baud, std::string_view framing) {
  const Rate* rate = find_rate(baud);
  const Framing* frame = find_framing(framing);
  if (rate == nullptr) return "baud " + std::to_string(baud) + " is not a supported rate";
  if (frame == nullptr) return "framing '" + std::string(framing) + "' is not supported";
  termios tio{};
  if (::tcgetattr(fd, &tio) != 0) return failed("not a terminal", errno);
  ::cfmakeraw(&tio);
  tio.c_cflag &= ~(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
  tio.c_cflag |= frame->size | frame->parity | frame->stop | CLOCAL | CREAD;
  // Parity checked, and a byte that fails it (or its framing) dropped rather than read as a NUL
  // (INPCK with IGNPAR): the decoders' checksums then refuse the message it was part of.
  if (frame->parity != 0) tio.c_iflag |= INPCK | IGNPAR;
  // VMIN 1: an empty non-blocking read says EAGAIN, so a read of 0 means the line hung up
  // (VMIN 0 would make "nothing yet" and "unplugged" look the same).
  tio.c_cc[VMIN] = 1;
  tio.c_cc[VTIME] = 0;
  if (::cfsetispeed(&tio, rate->speed) != 0 || ::cfsetospeed(&tio, rate->speed) != 0)
    return failed("cannot set " + std::to_string(baud) + " baud", errno);
  if (::tcsetattr(fd, TCSANOW, &tio) != 0) return failed("cannot set the line settings", errno);
  // tcsetattr succeeds if any one setting took: read back that the rate did.
  termios now{};
  if (::tcgetattr(fd, &now) != 0) return failed("cannot read the line settings back", errno);
  if (::cfgetospeed(&now) != rate->speed)
    return "the port refused " + std::to_string(baud) + " baud";
  ::tcflush(fd, TCIFLUSH);
  return {};
}

}  // namespace brickyard::drivers
