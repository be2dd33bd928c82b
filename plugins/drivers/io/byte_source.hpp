#pragma once
// The drivers' device I/O, framework-free: a sensor named by one string (the driver's `source`
// parameter) opened as a non-blocking byte source that a plugin polls from its periodic step, and
// the simulator's side of the same wires as a sink. Nothing here blocks after opening, reads a
// clock (the plugins stamp what they read with the run's clock) or throws on a device's errors:
// opening fails with a message naming the device and the OS error, a device that fails later says
// so through poll() and error(). A source reads, and a sink sends to, only what its spec names.
// docs/drivers-transports.md.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace brickyard::drivers {

// A device named by one string:
//   udp://HOST:PORT                       datagrams received on HOST:PORT (HOST an IPv4 address; 0.0.0.0 any)
//   udp://HOST:PORT?group=239.x.y.z       the same, joined to a multicast group (opt-in)
//   tcp://HOST:PORT                       a TCP client connected to HOST:PORT (a receiver's ICOM port)
//   serial:///dev/ttyX?baud=115200&framing=8N1   a serial port (termios raw; baud among the POSIX B* rates up to 921600; framing 8N1, 8E1, 8O1, 7E1, 8N2)
//   file://PATH?rate=R                    a recorded byte stream replayed (the plugin paces it; rate R > 0, default 1; 0 = as fast as read)
//   pcap://PATH?rate=R&port=P             a packet capture replayed (the plugin paces it; port filters UDP destination port, optional)
struct SourceSpec {
  enum class Kind { udp, tcp, serial, file, pcap };
  Kind kind = Kind::udp;
  std::string host;            // udp, tcp
  uint16_t port = 0;           // udp, tcp; pcap: destination-port filter (0: any)
  std::string group;           // udp: multicast group, empty none
  std::string path;            // serial, file, pcap
  int baud = 115200;           // serial
  std::string framing = "8N1"; // serial
  double rate = 1.0;           // file, pcap
  double reopen_s = 1.0;       // udp, tcp, serial: a device that failed is opened again this long after, s (0: never)
  std::string text;            // the spec as given (for messages)
};

// The spec parsed, or why not (naming the part that is wrong: "source 'udp://1.2.3:70000': port 70000 out of 1..65535").
struct ParsedSource {
  std::optional<SourceSpec> spec;
  std::string error;
};
ParsedSource parse_source(std::string_view text);

// A live device read without blocking. poll() appends what is waiting — one entry per datagram
// (udp) or per read (stream kinds) — and returns false once the device has failed (closed by
// the peer, read error, port unplugged): error() then says why, naming the device. It reads at
// most max_bytes per call so that one step is bounded (a datagram is never split: one larger than
// max_bytes comes alone, in a call of its own).
class ByteSource {
 public:
  virtual ~ByteSource() = default;
  virtual bool poll(std::vector<std::vector<uint8_t>>& out, size_t max_bytes = 1 << 20) = 0;
  virtual const std::string& error() const = 0;
  virtual bool datagrams() const = 0;  // true for udp: each entry is one packet
  // The descriptor to wait on for more (Context::wake_on_readable); -1 once the device failed.
  virtual int fd() const = 0;
  // The kernel's receive time of each entry the last poll() appended (ns since the epoch: the
  // real clock's), where the transport keeps one (udp: SO_TIMESTAMPNS); empty otherwise.
  virtual const std::vector<int64_t>& arrivals_ns() const {
    static const std::vector<int64_t> none;
    return none;
  }
};
// Opens a live device (udp, tcp, serial). Returns null with `error` naming the device and the OS error
// ("serial:///dev/ttyUSB9: cannot open: No such file or directory"). file and pcap are not live: error says so.
std::unique_ptr<ByteSource> open_source(const SourceSpec& spec, std::string& error);

// The simulator's side of the same wires: a sink that sends what a device would. udp://HOST:PORT
// sends datagrams to HOST:PORT; serial://PATH writes to a tty (the simulator uses a pty's master:
// see open_pty and pty_sink below); tcp://HOST:PORT listens on HOST:PORT and sends to every client
// connected (non-blocking accept on each send).
class ByteSink {
 public:
  virtual ~ByteSink() = default;
  virtual bool send(const uint8_t* data, size_t size) = 0;  // false on error(): never blocks (a full buffer: counted in dropped())
  virtual const std::string& error() const = 0;
  virtual uint64_t dropped() const = 0;  // bytes not sent because a buffer was full
};
std::unique_ptr<ByteSink> open_sink(const SourceSpec& spec, std::string& error);

// A pseudo-terminal pair: the master end for the simulator, the slave's path for the driver's serial:// source.
struct Pty {
  int master_fd = -1;
  std::string slave_path;
};
std::optional<Pty> open_pty(std::string& error);  // raw mode, non-blocking master; the caller closes master_fd
// A sink writing to a pty's master, which it then owns (closed with the sink): what the simulator
// sends reaches the driver reading pty.slave_path.
std::unique_ptr<ByteSink> pty_sink(const Pty& pty);

}  // namespace brickyard::drivers
