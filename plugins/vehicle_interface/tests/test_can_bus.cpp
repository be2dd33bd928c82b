// The bus named by one string: can://IFNAME and udp:// with send_to parsed (each mistake named),
// CAN frames through cannelloni datagrams on loopback both ways, lost datagrams counted from the
// sequence numbers, and a SocketCAN interface that does not exist named. (A real SocketCAN bus
// cannot be tested here: these machines have no vcan.)
#include "vehicle_interface/bus/can_bus.hpp"
#include "vehicle_interface/common/cannelloni.hpp"

#include "free_port.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <thread>

using namespace brickyard::vehicle_interface;

namespace {

std::string refusal(const std::string& bus, const std::string& send_to, std::string* param_out = nullptr) {
  std::string error, param;
  EXPECT_FALSE(parse_bus(bus, send_to, error, param)) << bus;
  if (param_out) *param_out = param;
  return error;
}

std::unique_ptr<CanBus> udp_bus(uint16_t listen, uint16_t to) {
  std::string error, param;
  const std::optional<BusSpec> spec =
      parse_bus("udp://127.0.0.1:" + std::to_string(listen), "udp://127.0.0.1:" + std::to_string(to), error, param);
  EXPECT_TRUE(spec) << error;
  std::unique_ptr<CanBus> bus = open_bus(*spec, error);
  EXPECT_TRUE(bus) << error;
  return bus;
}

std::vector<CanFrame> poll_for(CanBus& bus, size_t want) {
  std::vector<CanFrame> got;
  for (int i = 0; i < 400 && got.size() < want; ++i) {
    EXPECT_TRUE(bus.poll(got)) << bus.error();
    if (got.size() < want) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return got;
}

CanFrame frame(uint32_t id, uint8_t first) {
  CanFrame f;
  f.id = id;
  f.length = 8;
  f.data[0] = first;
  return f;
}

}  // namespace

TEST(ParseBus, ReadsBothKindsAndNamesWhatIsWrong) {
  std::string error, param;
  std::optional<BusSpec> s = parse_bus("can://can0", "", error, param);
  ASSERT_TRUE(s) << error;
  EXPECT_EQ(s->kind, BusSpec::Kind::socketcan);
  EXPECT_EQ(s->interface, "can0");
  s = parse_bus("udp://127.0.0.1:20001", "udp://127.0.0.1:20002", error, param);
  ASSERT_TRUE(s) << error;
  EXPECT_EQ(s->kind, BusSpec::Kind::udp);
  EXPECT_EQ(s->listen.port, 20001);
  EXPECT_EQ(s->send_to.port, 20002);
  EXPECT_EQ(refusal("can://", ""), "'can://': no interface named");
  EXPECT_EQ(refusal("can://abcdefghijklmnop", ""), "'can://abcdefghijklmnop': interface name over 15 characters");
  EXPECT_EQ(refusal("can://ca n0", ""), "'can://ca n0': 'ca n0' is no interface name");
  std::string which;
  EXPECT_EQ(refusal("can://can0", "udp://127.0.0.1:1", &which), "a can:// bus sends on its interface; send_to is for udp:// only");
  EXPECT_EQ(which, "send_to");
  EXPECT_EQ(refusal("udp://127.0.0.1:20001", "", &which), "a udp:// bus needs send_to, udp://HOST:PORT (where the frames go)");
  EXPECT_EQ(which, "send_to");
  EXPECT_EQ(refusal("udp://127.0.0.1:70000", "udp://127.0.0.1:1", &which), "source 'udp://127.0.0.1:70000': port 70000 out of 1..65535");
  EXPECT_EQ(which, "bus");
  EXPECT_EQ(refusal("tcp://127.0.0.1:3001", "udp://127.0.0.1:1"),
            "'tcp://127.0.0.1:3001': a bus is can://IFNAME, or udp://HOST:PORT with send_to udp://HOST:PORT");
  EXPECT_EQ(refusal("udp://127.0.0.1:20001", "serial:///dev/ttyS0", &which),
            "'serial:///dev/ttyS0': a bus is can://IFNAME, or udp://HOST:PORT with send_to udp://HOST:PORT");
  EXPECT_EQ(which, "send_to");
}

// Two ends of a bus on loopback (the interface's and the simulator's): frames both ways, in order.
TEST(UdpBus, CarriesFramesBothWaysInCannelloniDatagrams) {
  const uint16_t a = free_port(), b = free_port();
  std::unique_ptr<CanBus> car = udp_bus(a, b), dbw = udp_bus(b, a);
  ASSERT_TRUE(car && dbw);
  std::vector<CanFrame> sent;
  for (uint8_t i = 0; i < 5; ++i) sent.push_back(frame(1400 + i, i));
  ASSERT_TRUE(car->send(sent));
  EXPECT_EQ(poll_for(*dbw, 5), sent);
  ASSERT_TRUE(dbw->send({frame(1300, 9)}));
  EXPECT_EQ(poll_for(*car, 1), std::vector<CanFrame>{frame(1300, 9)});
  EXPECT_EQ(car->counts().frames_out, 5u);
  EXPECT_EQ(dbw->counts().frames_in, 5u);
  EXPECT_EQ(dbw->counts().datagrams_in, 1u);
  EXPECT_EQ(dbw->counts().datagrams_lost, 0u);
}

// Datagrams from another sender: one whose sequence number skips three counts three lost; one
// that is no cannelloni datagram is refused and counted.
TEST(UdpBus, CountsLostAndRefusedDatagrams) {
  const uint16_t a = free_port(), b = free_port();
  std::unique_ptr<CanBus> bus = udp_bus(a, b);
  std::unique_ptr<CanBus> raw = udp_bus(b, a);  // sends as it likes, through its own encoder below
  ASSERT_TRUE(bus && raw);
  int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(a);
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  auto send = [&](const std::vector<uint8_t>& d) {
    ASSERT_EQ(::sendto(fd, d.data(), d.size(), 0, reinterpret_cast<sockaddr*>(&to), sizeof to), static_cast<ssize_t>(d.size()));
  };
  for (uint8_t seq : {10, 11, 15}) {
    uint8_t next = seq;
    send(encode_cannelloni({frame(1300, seq)}, next).datagrams.front());
  }
  send({1, 2, 3});  // short: refused
  EXPECT_EQ(poll_for(*bus, 3).size(), 3u);
  std::vector<CanFrame> more;
  for (int i = 0; i < 100 && bus->counts().datagrams_refused == 0; ++i) {
    bus->poll(more);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(bus->counts().datagrams_in, 4u);
  EXPECT_EQ(bus->counts().datagrams_lost, 3u);  // 12, 13, 14
  EXPECT_EQ(bus->counts().datagrams_refused, 1u);
  ::close(fd);
}

TEST(SocketCanBus, AnInterfaceThatDoesNotExistIsNamed) {
  std::string error, param;
  const std::optional<BusSpec> spec = parse_bus("can://bynocan7", "", error, param);
  ASSERT_TRUE(spec);
  EXPECT_FALSE(open_bus(*spec, error));
  EXPECT_EQ(error, "can://bynocan7: no such network interface (ip link shows the CAN interfaces)");
  // An interface that exists but is no CAN interface: the socket or the bind is refused, named.
  const std::optional<BusSpec> lo = parse_bus("can://lo", "", error, param);
  EXPECT_FALSE(open_bus(*lo, error));
  EXPECT_EQ(error.rfind("can://lo: cannot ", 0), 0u) << error;
}
