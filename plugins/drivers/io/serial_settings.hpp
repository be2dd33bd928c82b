#pragma once
// A serial port's line settings: which rates and framings a serial:// spec may name, and the
// termios that puts a tty in raw mode at them. One table serves both, so a spec that parses is
// one the port can be asked for.
#include <string>
#include <string_view>

namespace brickyard::drivers {

bool serial_baud_supported(int baud);
bool serial_framing_supported(std::string_view framing);
// The rates and framings, for messages: "50, 75, ... 921600" and "8N1, 8E1, 8O1, 7E1, 8N2".
std::string serial_bauds_listed();
std::string serial_framings_listed();

// Puts the tty `fd` in raw mode (no echo, no line editing, no translation, no flow control, modem
// lines ignored) at `baud` and `framing`, reads that return at once (the fd is non-blocking), and
// discards what arrived before (stale bytes would be stamped with this run's clock). Returns
// empty, or what failed ("cannot set 921600 baud: Invalid argument") for the caller to prefix
// with the device.
std::string configure_serial(int fd, int baud, std::string_view framing);

}  // namespace brickyard::drivers
