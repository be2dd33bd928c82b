#pragma once
// The vehicle interface's CAN bus, named by one string and used without blocking (docs/vehicle-interface.md, "The bus"):
//   can://IFNAME                 a SocketCAN interface (the car's can0), raw frames, classic and CAN FD
//   udp://HOST:PORT + send_to    CAN frames over UDP in cannelloni's datagrams (common/cannelloni.hpp):
//                                received on HOST:PORT, sent to send_to's udp://HOST:PORT (tests, the
//                                simulator, or cannelloni bridging a real bus)
// poll() reads what is waiting and returns; send() never waits (what the kernel does not take is
// dropped and counted). Opening fails with a message naming the bus; a bus that fails later says
// so through error(). No clock is read. Framework-free (POSIX sockets).
#include "drivers/io/byte_source.hpp"
#include "vehicle_interface/common/can_frame.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace brickyard::vehicle_interface {

struct BusSpec {
  enum class Kind { udp, socketcan };
  Kind kind = Kind::udp;
  drivers::SourceSpec listen;   // udp: where frames are received
  drivers::SourceSpec send_to;  // udp: where frames are sent
  std::string interface;        // socketcan: the interface's name
  std::string text;             // the bus as given
};

// The bus and, for udp://, where to send; or nullopt, `error` saying what is wrong and `param`
// which of the two it is ("bus": "'can://': no interface named"; "send_to": "a udp:// bus needs
// send_to, udp://HOST:PORT").
std::optional<BusSpec> parse_bus(const std::string& bus, const std::string& send_to, std::string& error, std::string& param);

struct BusCounts {
  uint64_t frames_in = 0, frames_out = 0;
  uint64_t frames_dropped = 0;   // not taken by the kernel (a full buffer)
  uint64_t error_frames = 0;     // CAN error frames received: passed over
  uint64_t datagrams_in = 0, datagrams_refused = 0, datagrams_lost = 0;  // udp: cannelloni's
};

class CanBus {
 public:
  virtual ~CanBus() = default;
  // Appends the frames waiting (at most max_frames); false once the bus has failed (error() says why).
  virtual bool poll(std::vector<CanFrame>& out, size_t max_frames = 4096) = 0;
  // Sends the frames (udp: in as few datagrams as hold them); false once the bus has failed.
  virtual bool send(const std::vector<CanFrame>& frames) = 0;
  virtual const std::string& error() const = 0;
  virtual const BusCounts& counts() const = 0;
};

// Opens the bus: null and `error` naming it ("can://can9: no such network interface") when it cannot.
std::unique_ptr<CanBus> open_bus(const BusSpec& spec, std::string& error);

// One udp://HOST:PORT alone ("'tcp://x:1': a bus is can://IFNAME, or udp://HOST:PORT ...").
std::optional<drivers::SourceSpec> parse_udp_address(const std::string& text, std::string& error);
// Cannelloni over UDP one way only: a receiver (send() takes no frames: false, error() says so)
// for a second peer's frames on a port of their own, a sender (poll() finds none) for a peer that
// only talks (the simulated race control). Each peer numbers its datagrams: two on one port would
// garble the count of datagrams lost.
std::unique_ptr<CanBus> open_udp_receiver(const drivers::SourceSpec& listen, std::string& error);
std::unique_ptr<CanBus> open_udp_sender(const drivers::SourceSpec& to, std::string& error);

// The two kinds, each in its own file.
std::unique_ptr<CanBus> open_udp_bus(const BusSpec& spec, std::string& error);
std::unique_ptr<CanBus> open_socketcan_bus(const BusSpec& spec, std::string& error);

}  // namespace brickyard::vehicle_interface
