// The transports against real descriptors: parse_source's answers and refusals, a pty pair both
// ways, UDP and TCP on 127.0.0.1 (ports the kernel picked free), a device's failure reported by
// poll, and the bound on one poll. Bytes are compared exactly. Tests may sleep to wait for the
// kernel; the transports never do.
#include "drivers/io/byte_source.hpp"
#include "drivers/io/reopening_device.hpp"

#include "free_port.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace brickyard::drivers {
namespace {

using Entries = std::vector<std::vector<uint8_t>>;
using std::chrono_literals::operator""ms;

std::vector<uint8_t> bytes_of(std::string_view text) { return {text.begin(), text.end()}; }

SourceSpec spec_of(const std::string& text) {
  ParsedSource parsed = parse_source(text);
  EXPECT_TRUE(parsed.spec) << parsed.error;
  return parsed.spec.value_or(SourceSpec{});
}

std::string refusal(std::string_view text) {
  ParsedSource parsed = parse_source(text);
  EXPECT_FALSE(parsed.spec) << text;
  return parsed.error;
}

// A UDP source and a sink sending to it, on a free loopback port (`query`: the spec's "?..." part).
struct UdpPair {
  std::unique_ptr<ByteSource> source;
  std::unique_ptr<ByteSink> sink;
  std::string error;
};
UdpPair udp_pair(const std::string& query = "") {
  UdpPair p;
  const std::string name = "udp://127.0.0.1:" + std::to_string(free_port(SOCK_DGRAM)) + query;
  p.source = open_source(spec_of(name), p.error);
  if (p.source) p.sink = open_sink(spec_of(name), p.error);
  return p;
}

// Polls (short sleeps, two seconds at most) until `want` bytes have come; the entries read.
Entries poll_for(ByteSource& source, size_t want, size_t max_bytes = 1 << 20) {
  Entries entries;
  size_t got = 0;
  for (int i = 0; i < 400 && got < want; ++i) {
    size_t before = entries.size();
    EXPECT_TRUE(source.poll(entries, max_bytes)) << source.error();
    for (size_t e = before; e < entries.size(); ++e) got += entries[e].size();
    if (got < want) std::this_thread::sleep_for(5ms);
  }
  return entries;
}

std::vector<uint8_t> joined(const Entries& entries) {
  std::vector<uint8_t> all;
  for (const auto& e : entries) all.insert(all.end(), e.begin(), e.end());
  return all;
}

// Every byte value, then text: a raw tty passes all 256 unchanged (no CR/LF translation, no echo).
std::vector<uint8_t> all_byte_values() {
  std::vector<uint8_t> data;
  for (int i = 0; i < 256; ++i) data.push_back(static_cast<uint8_t>(i));
  for (uint8_t c : bytes_of("\r\n$GPGGA,1*00\r\n\x03\x04")) data.push_back(c);
  return data;
}

// A pty whose master is closed at the end of the test unless handed on.
struct PtyPair {
  Pty pty;
  PtyPair() {
    std::string error;
    auto opened = open_pty(error);
    EXPECT_TRUE(opened) << error;
    if (opened) pty = *opened;
  }
  ~PtyPair() {
    if (pty.master_fd >= 0) ::close(pty.master_fd);
  }
};

TEST(ParseSource, ReadsEachKind) {
  SourceSpec udp = spec_of("udp://0.0.0.0:7502");
  EXPECT_EQ(udp.kind, SourceSpec::Kind::udp);
  EXPECT_EQ(udp.host, "0.0.0.0");
  EXPECT_EQ(udp.port, 7502);
  EXPECT_EQ(udp.group, "");
  EXPECT_EQ(udp.text, "udp://0.0.0.0:7502");

  SourceSpec multicast = spec_of("udp://192.168.1.5:7502?group=239.1.2.3");
  EXPECT_EQ(multicast.host, "192.168.1.5");
  EXPECT_EQ(multicast.group, "239.1.2.3");

  SourceSpec tcp = spec_of("tcp://10.0.0.2:3001");
  EXPECT_EQ(tcp.kind, SourceSpec::Kind::tcp);
  EXPECT_EQ(tcp.host, "10.0.0.2");
  EXPECT_EQ(tcp.port, 3001);

  SourceSpec serial = spec_of("serial:///dev/ttyUSB0?baud=921600&framing=7E1");
  EXPECT_EQ(serial.kind, SourceSpec::Kind::serial);
  EXPECT_EQ(serial.path, "/dev/ttyUSB0");
  EXPECT_EQ(serial.baud, 921600);
  EXPECT_EQ(serial.framing, "7E1");
  SourceSpec serial_defaults = spec_of("serial:///dev/ttyS1");
  EXPECT_EQ(serial_defaults.baud, 115200);
  EXPECT_EQ(serial_defaults.framing, "8N1");

  SourceSpec file = spec_of("file://data/gnss/run.bin?rate=2.5");
  EXPECT_EQ(file.kind, SourceSpec::Kind::file);
  EXPECT_EQ(file.path, "data/gnss/run.bin");
  EXPECT_EQ(file.rate, 2.5);
  EXPECT_EQ(spec_of("file:///tmp/x.bin").rate, 1.0);
  EXPECT_EQ(spec_of("file:///tmp/x.bin?rate=0").rate, 0.0);

  SourceSpec pcap = spec_of("pcap:///data/os1.pcap?rate=1&port=7502");
  EXPECT_EQ(pcap.kind, SourceSpec::Kind::pcap);
  EXPECT_EQ(pcap.path, "/data/os1.pcap");
  EXPECT_EQ(pcap.port, 7502);
  EXPECT_EQ(spec_of("pcap://a.pcap").port, 0);
}

TEST(ParseSource, NamesWhatIsWrong) {
  EXPECT_EQ(refusal("udp://1.2.3:70000"), "source 'udp://1.2.3:70000': port 70000 out of 1..65535");
  EXPECT_EQ(refusal("udp://1.2.3:7000"),
            "source 'udp://1.2.3:7000': host '1.2.3' is not an IPv4 address (names are not resolved)");
  EXPECT_EQ(refusal("tcp://receiver.local:3001"),
            "source 'tcp://receiver.local:3001': host 'receiver.local' is not an IPv4 address (names are not resolved)");
  EXPECT_EQ(refusal("udp://127.0.0.1:0"), "source 'udp://127.0.0.1:0': port 0 out of 1..65535");
  EXPECT_EQ(refusal("udp://127.0.0.1:lidar"), "source 'udp://127.0.0.1:lidar': port 'lidar' is not a number");
  EXPECT_EQ(refusal("udp://127.0.0.1"), "source 'udp://127.0.0.1': expected HOST:PORT, got '127.0.0.1'");
  EXPECT_EQ(refusal("tcp://:3001"), "source 'tcp://:3001': host missing before ':'");
  EXPECT_EQ(refusal("udp://0.0.0.0:7502?group=10.1.1.1"),
            "source 'udp://0.0.0.0:7502?group=10.1.1.1': group '10.1.1.1' is not an IPv4 multicast address "
            "(224.0.0.0 to 239.255.255.255)");
  EXPECT_EQ(refusal("tcp://10.0.0.2:3001?group=239.1.1.1"),
            "source 'tcp://10.0.0.2:3001?group=239.1.1.1': unknown parameter 'group' for tcp (takes: reopen)");
  EXPECT_EQ(refusal("http://x"), "source 'http://x': unknown scheme 'http' (udp, tcp, serial, file, pcap)");
  EXPECT_EQ(refusal("/dev/ttyUSB0"),
            "source '/dev/ttyUSB0': expected SCHEME://..., SCHEME one of udp, tcp, serial, file, pcap");
  EXPECT_EQ(refusal("serial://dev/ttyUSB0"),
            "source 'serial://dev/ttyUSB0': path 'dev/ttyUSB0' is not absolute (serial:///dev/ttyUSB0)");
  EXPECT_EQ(refusal("serial://"), "source 'serial://': path missing");
  EXPECT_EQ(refusal("serial:///dev/ttyS0?baud=fast"), "source 'serial:///dev/ttyS0?baud=fast': baud 'fast' is not a number");
  EXPECT_EQ(refusal("serial:///dev/ttyS0?framing=9N1"),
            "source 'serial:///dev/ttyS0?framing=9N1': framing '9N1' is not one of 8N1, 8E1, 8O1, 7E1, 8N2");
  EXPECT_EQ(refusal("serial:///dev/ttyS0?baud=115200&baud=9600"),
            "source 'serial:///dev/ttyS0?baud=115200&baud=9600': parameter 'baud' given twice");
  EXPECT_EQ(refusal("serial:///dev/ttyS0?parity=even"),
            "source 'serial:///dev/ttyS0?parity=even': unknown parameter 'parity' for serial (takes: baud, framing, reopen)");
  EXPECT_EQ(refusal("serial:///dev/ttyS0?baud="), "source 'serial:///dev/ttyS0?baud=': parameter 'baud' has no value");
  EXPECT_EQ(refusal("serial:///dev/ttyS0?&baud=9600"), "source 'serial:///dev/ttyS0?&baud=9600': empty parameter in the query");
  EXPECT_EQ(refusal("file://run.bin?rate=-1"),
            "source 'file://run.bin?rate=-1': rate -1 must be finite and 0 (as fast as read) or more");
  EXPECT_EQ(refusal("file://run.bin?rate=inf"),
            "source 'file://run.bin?rate=inf': rate inf must be finite and 0 (as fast as read) or more");
  EXPECT_EQ(refusal("file://run.bin?rate=fast"), "source 'file://run.bin?rate=fast': rate 'fast' is not a number");
  EXPECT_EQ(refusal("file://"), "source 'file://': path missing");
  EXPECT_EQ(refusal("tcp://10.0.0.2:3001?reopen=-1"),
            "source 'tcp://10.0.0.2:3001?reopen=-1': reopen -1 must be finite and 0 (never) or more");
  EXPECT_EQ(refusal("file://run.bin?reopen=1"), "source 'file://run.bin?reopen=1': unknown parameter 'reopen' for file (takes: rate)");
  EXPECT_EQ(refusal("pcap://os1.pcap?port=99999"), "source 'pcap://os1.pcap?port=99999': filter port 99999 out of 1..65535");
  EXPECT_EQ(refusal("pcap://os1.pcap?group=239.1.1.1"),
            "source 'pcap://os1.pcap?group=239.1.1.1': unknown parameter 'group' for pcap (takes: rate, port)");
}

TEST(ParseSource, RefusesABaudThatIsNotAPosixRate) {
  std::string error = refusal("serial:///dev/ttyS0?baud=100000");
  EXPECT_EQ(error.rfind("source 'serial:///dev/ttyS0?baud=100000': baud 100000 is not one of the POSIX rates (50, 75,", 0), 0u)
      << error;
  EXPECT_NE(error.find("115200, 230400, 460800, 500000, 576000, 921600)"), std::string::npos) << error;
  EXPECT_FALSE(parse_source("serial:///dev/ttyS0?baud=1843200").spec);  // above 921600
  EXPECT_FALSE(parse_source("serial:///dev/ttyS0?baud=0").spec);        // B0 hangs up; it is no rate
  EXPECT_FALSE(parse_source("serial:///dev/ttyS0?baud=-9600").spec);
  EXPECT_TRUE(parse_source("serial:///dev/ttyS0?baud=50").spec);
}

TEST(Serial, PtyBytesReachTheSourceInOrder) {
  PtyPair pair;
  std::string error;
  auto source = open_source(spec_of("serial://" + pair.pty.slave_path + "?baud=115200&framing=8N1"), error);
  ASSERT_TRUE(source) << error;
  EXPECT_EQ(error, "");
  EXPECT_FALSE(source->datagrams());
  std::vector<uint8_t> sent = all_byte_values();
  ASSERT_EQ(::write(pair.pty.master_fd, sent.data(), sent.size()), static_cast<ssize_t>(sent.size()));
  EXPECT_EQ(joined(poll_for(*source, sent.size())), sent);
  Entries more;
  EXPECT_TRUE(source->poll(more));
  EXPECT_TRUE(more.empty());
}

TEST(Serial, SinkBytesReachThePtyMaster) {
  PtyPair pair;
  std::string error;
  auto sink = open_sink(spec_of("serial://" + pair.pty.slave_path), error);
  ASSERT_TRUE(sink) << error;
  std::vector<uint8_t> sent = all_byte_values();
  ASSERT_TRUE(sink->send(sent.data(), sent.size())) << sink->error();
  std::vector<uint8_t> got;
  for (int i = 0; i < 400 && got.size() < sent.size(); ++i) {
    uint8_t buffer[512];
    ssize_t n = ::read(pair.pty.master_fd, buffer, sizeof buffer);
    if (n > 0) got.insert(got.end(), buffer, buffer + n);
    else std::this_thread::sleep_for(5ms);
  }
  EXPECT_EQ(got, sent);
  EXPECT_EQ(sink->dropped(), 0u);
}

TEST(Serial, PtySinkFeedsASerialSource) {
  PtyPair pair;
  std::string error;
  auto source = open_source(spec_of("serial://" + pair.pty.slave_path + "?baud=9600&framing=8N2"), error);
  ASSERT_TRUE(source) << error;
  auto sink = pty_sink(pair.pty);
  pair.pty.master_fd = -1;  // the sink's now
  std::vector<uint8_t> sent = all_byte_values();
  ASSERT_TRUE(sink->send(sent.data(), sent.size())) << sink->error();
  EXPECT_EQ(joined(poll_for(*source, sent.size())), sent);
}

// A line left cooked (echo, canonical input, CR to NL, NL to CR NL on output) is made raw by the
// opening, at the spec's rate and framing.
TEST(Serial, OpeningSetsRawModeRateAndFraming) {
  PtyPair pair;
  termios cooked{};
  ASSERT_EQ(::tcgetattr(pair.pty.master_fd, &cooked), 0);  // Linux: the slave's settings
  cooked.c_lflag |= ICANON | ECHO | ISIG;
  cooked.c_iflag |= ICRNL;
  cooked.c_oflag |= OPOST | ONLCR;
  ASSERT_EQ(::tcsetattr(pair.pty.master_fd, TCSANOW, &cooked), 0);
  std::string error;
  auto source = open_source(spec_of("serial://" + pair.pty.slave_path + "?baud=921600&framing=8N2"), error);
  ASSERT_TRUE(source) << error;
  termios now{};
  ASSERT_EQ(::tcgetattr(pair.pty.master_fd, &now), 0);
  EXPECT_EQ(::cfgetospeed(&now), static_cast<speed_t>(B921600));
  // Linux's pty forces CS8 without parity (a 7E1 would not show); the stop bits it keeps.
  EXPECT_EQ(now.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
  EXPECT_EQ(now.c_cflag & (PARENB | PARODD | CSTOPB), static_cast<tcflag_t>(CSTOPB));
  EXPECT_EQ(now.c_lflag & (ICANON | ECHO | ISIG), 0u);
  std::vector<uint8_t> sent = all_byte_values();
  ASSERT_EQ(::write(pair.pty.master_fd, sent.data(), sent.size()), static_cast<ssize_t>(sent.size()));
  EXPECT_EQ(joined(poll_for(*source, sent.size())), sent);
  uint8_t echoed[64];
  EXPECT_EQ(::read(pair.pty.master_fd, echoed, sizeof echoed), -1);  // nothing echoed back
}

TEST(Serial, AHungUpLineFailsThePollNamingTheDevice) {
  PtyPair pair;
  std::string error;
  std::string name = "serial://" + pair.pty.slave_path;
  auto source = open_source(spec_of(name), error);
  ASSERT_TRUE(source) << error;
  ::close(pair.pty.master_fd);  // the port unplugged
  pair.pty.master_fd = -1;
  Entries entries;
  bool alive = true;
  for (int i = 0; i < 400 && alive; ++i) {
    alive = source->poll(entries);
    if (alive) std::this_thread::sleep_for(5ms);
  }
  EXPECT_FALSE(alive);
  EXPECT_EQ(source->error().rfind(name + ": ", 0), 0u) << source->error();
  EXPECT_FALSE(source->poll(entries));  // and stays failed
}

TEST(Serial, AMissingDeviceIsNamed) {
  std::string error;
  auto source = open_source(spec_of("serial:///dev/ttyUSB_brickyard_none?baud=115200"), error);
  EXPECT_FALSE(source);
  EXPECT_EQ(error, "serial:///dev/ttyUSB_brickyard_none?baud=115200: cannot open: No such file or directory");
  auto sink = open_sink(spec_of("serial:///dev/ttyUSB_brickyard_none"), error);
  EXPECT_FALSE(sink);
  EXPECT_EQ(error, "serial:///dev/ttyUSB_brickyard_none: cannot open: No such file or directory");
}

TEST(Serial, NotATerminalIsRefused) {
  std::string error;
  EXPECT_FALSE(open_source(spec_of("serial:///dev/null"), error));
  EXPECT_EQ(error, "serial:///dev/null: not a terminal: Inappropriate ioctl for device");
}

TEST(Serial, ABaudNotParsedIsStillRefusedAtOpen) {
  PtyPair pair;
  SourceSpec spec;  // built in code, not parsed: the opener checks again
  spec.kind = SourceSpec::Kind::serial;
  spec.path = pair.pty.slave_path;
  spec.baud = 12345;
  std::string error;
  EXPECT_FALSE(open_source(spec, error));
  EXPECT_EQ(error, "serial://" + pair.pty.slave_path + ": baud 12345 is not a supported rate");
}

TEST(Serial, AFullLineDropsInsteadOfBlocking) {
  PtyPair pair;
  std::string error;
  auto source = open_source(spec_of("serial://" + pair.pty.slave_path), error);  // opened, never read
  ASSERT_TRUE(source) << error;
  auto sink = pty_sink(pair.pty);
  pair.pty.master_fd = -1;
  std::vector<uint8_t> chunk(4096, 0x55);
  for (int i = 0; i < 256; ++i) ASSERT_TRUE(sink->send(chunk.data(), chunk.size())) << sink->error();
  EXPECT_GT(sink->dropped(), 0u);  // a pty holds far less than 1 MiB
  EXPECT_LT(sink->dropped(), 256u * 4096u);
}

TEST(Udp, DatagramsArriveWhole) {
  auto [source, sink, error] = udp_pair();
  ASSERT_TRUE(source && sink) << error;
  EXPECT_TRUE(source->datagrams());
  Entries sent = {bytes_of("first"), std::vector<uint8_t>(1500, 0xAB), bytes_of("x"), std::vector<uint8_t>(60000, 7)};
  for (const auto& d : sent) ASSERT_TRUE(sink->send(d.data(), d.size())) << sink->error();
  Entries got = poll_for(*source, 5 + 1500 + 1 + 60000);
  EXPECT_EQ(got, sent);
  EXPECT_EQ(sink->dropped(), 0u);
}

TEST(Udp, OnePollReadsAtMostMaxBytes) {
  auto [source, sink, error] = udp_pair();
  ASSERT_TRUE(source && sink) << error;
  Entries sent;
  for (int i = 0; i < 10; ++i) sent.push_back(std::vector<uint8_t>(100, static_cast<uint8_t>(i)));
  sent.push_back(std::vector<uint8_t>(400, 0xEE));  // larger than the bound: comes alone
  for (const auto& d : sent) ASSERT_TRUE(sink->send(d.data(), d.size()));
  std::this_thread::sleep_for(50ms);  // all queued before the first poll, so the bound is what stops it
  Entries got;
  std::vector<size_t> per_poll;
  for (int i = 0; i < 400 && got.size() < sent.size(); ++i) {
    Entries one;
    ASSERT_TRUE(source->poll(one, 250)) << source->error();
    size_t bytes = joined(one).size();
    if (bytes > 0) per_poll.push_back(bytes);
    got.insert(got.end(), one.begin(), one.end());
    if (one.empty()) std::this_thread::sleep_for(5ms);
  }
  EXPECT_EQ(got, sent);
  EXPECT_EQ(per_poll, (std::vector<size_t>{200, 200, 200, 200, 200, 400}));
}

// Each datagram carries the kernel's receive time, on the real clock's scale (the epoch's), the
// held one too; the descriptor is one poll() on it wakes for.
TEST(Udp, EachDatagramHasItsArrivalAndTheDescriptorWakes) {
  auto [source, sink, error] = udp_pair();
  ASSERT_TRUE(source && sink) << error;
  ASSERT_GE(source->fd(), 0);
  pollfd idle{source->fd(), POLLIN, 0};
  EXPECT_EQ(::poll(&idle, 1, 0), 0);  // nothing yet
  auto epoch_ns = [] { return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::system_clock::now().time_since_epoch()).count(); };
  const int64_t before = epoch_ns();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(sink->send(std::vector<uint8_t>(100, 1).data(), 100));
  pollfd ready{source->fd(), POLLIN, 0};
  ASSERT_EQ(::poll(&ready, 1, 2000), 1);
  std::this_thread::sleep_for(20ms);
  Entries first, second;
  ASSERT_TRUE(source->poll(first, 250));  // two fit: the third is read and held for the next poll
  // Read by now: the kernel stamps a datagram as it arrives, or (its timestamping switched on
  // lazily, for the first datagrams after the socket asks) as it is read.
  const int64_t after = epoch_ns();
  ASSERT_EQ(first.size(), 2u);
  std::vector<int64_t> arrivals = source->arrivals_ns();
  ASSERT_TRUE(source->poll(second, 250));
  ASSERT_EQ(second.size(), 1u);
  ASSERT_EQ(source->arrivals_ns().size(), 1u);
  arrivals.push_back(source->arrivals_ns()[0]);
  ASSERT_EQ(arrivals.size(), 3u);
  for (int64_t a : arrivals) {
    EXPECT_GE(a, before);
    EXPECT_LE(a, after);
  }
  Entries none;
  ASSERT_TRUE(source->poll(none));
  EXPECT_TRUE(none.empty());
  EXPECT_TRUE(source->arrivals_ns().empty());  // of the last poll only
}

// The group joined, and sent to, on loopback's interface (127.0.0.1) with a TTL of 1: it stays on the machine.
TEST(Udp, AMulticastGroupIsJoinedWhenAsked) {
  auto [source, sink, error] = udp_pair("?group=239.255.42.7");
  ASSERT_TRUE(source && sink) << error;
  Entries sent = {bytes_of("lidar packet"), bytes_of("imu packet")};
  for (const auto& d : sent) ASSERT_TRUE(sink->send(d.data(), d.size())) << sink->error();
  EXPECT_EQ(poll_for(*source, 22), sent);
}

TEST(Udp, ABindThatFailsNamesTheDeviceAndTheOsError) {
  std::string error;
  // 192.0.2.1 (TEST-NET-1, RFC 5737) is no address of this machine.
  EXPECT_FALSE(open_source(spec_of("udp://192.0.2.1:7502"), error));
  EXPECT_EQ(error, "udp://192.0.2.1:7502: cannot bind 192.0.2.1:7502: Cannot assign requested address");
}

TEST(Tcp, ListeningSinkFeedsAClientSourceUntilItCloses) {
  uint16_t port = free_port(SOCK_STREAM);
  std::string name = "tcp://127.0.0.1:" + std::to_string(port);
  std::string error;
  auto sink = open_sink(spec_of(name), error);
  ASSERT_TRUE(sink) << error;
  auto source = open_source(spec_of(name), error);
  ASSERT_TRUE(source) << error;
  EXPECT_FALSE(source->datagrams());
  // Until the sink has accepted the client, what it sends reaches no one: probe with 'x' until
  // one arrives, then every byte of the message must follow, in order.
  Entries got;
  const uint8_t probe = 'x';
  for (int i = 0; i < 400 && got.empty(); ++i) {
    ASSERT_TRUE(sink->send(&probe, 1)) << sink->error();
    std::this_thread::sleep_for(5ms);
    ASSERT_TRUE(source->poll(got)) << source->error();
  }
  ASSERT_FALSE(got.empty());
  std::vector<uint8_t> message = all_byte_values();
  message[0] = '#';
  ASSERT_TRUE(sink->send(message.data(), message.size()));
  std::vector<uint8_t> received = joined(got), body;
  for (int i = 0; i < 400 && body.size() < message.size(); ++i) {
    std::this_thread::sleep_for(5ms);
    ASSERT_TRUE(source->poll(got)) << source->error();
    received = joined(got);
    size_t probes = 0;
    while (probes < received.size() && received[probes] == probe) ++probes;
    body.assign(received.begin() + static_cast<std::ptrdiff_t>(probes), received.end());
  }
  EXPECT_EQ(body, message);

  sink.reset();  // the receiver goes away
  Entries after;
  bool alive = true;
  for (int i = 0; i < 400 && alive; ++i) {
    alive = source->poll(after);
    if (alive) std::this_thread::sleep_for(5ms);
  }
  EXPECT_FALSE(alive);
  EXPECT_EQ(source->error(), name + ": closed by the peer");
}

TEST(Tcp, AClientLeavingDoesNotFailTheSink) {
  uint16_t port = free_port(SOCK_STREAM);
  std::string name = "tcp://127.0.0.1:" + std::to_string(port);
  std::string error;
  auto sink = open_sink(spec_of(name), error);
  auto source = open_source(spec_of(name), error);
  ASSERT_TRUE(sink && source) << error;
  std::vector<uint8_t> message(1000, 1);
  for (int i = 0; i < 20; ++i) {
    ASSERT_TRUE(sink->send(message.data(), message.size())) << sink->error();
    std::this_thread::sleep_for(2ms);
    if (i == 5) source.reset();
  }
  EXPECT_EQ(sink->error(), "");
}

TEST(Tcp, NoListenerIsReportedNamingTheDevice) {
  uint16_t port = free_port(SOCK_STREAM);  // free: nothing listens there
  std::string name = "tcp://127.0.0.1:" + std::to_string(port);
  std::string error;
  auto source = open_source(spec_of(name), error);
  if (!source) {
    EXPECT_EQ(error, name + ": cannot connect: Connection refused");  // known at once
    return;
  }
  Entries entries;
  bool alive = true;
  for (int i = 0; i < 400 && alive; ++i) {
    alive = source->poll(entries);
    if (alive) std::this_thread::sleep_for(5ms);
  }
  EXPECT_FALSE(alive);
  EXPECT_EQ(source->error(), name + ": connection failed: Connection refused");
}

TEST(Open, ReplaysAreNotLiveDevices) {
  std::string error;
  EXPECT_FALSE(open_source(spec_of("file://run.bin?rate=2"), error));
  EXPECT_EQ(error, "file://run.bin?rate=2: not a live device: the driver replays it, paced by the run's clock");
  EXPECT_FALSE(open_source(spec_of("pcap://os1.pcap"), error));
  EXPECT_EQ(error, "pcap://os1.pcap: not a live device: the driver replays it, paced by the run's clock");
  EXPECT_FALSE(open_sink(spec_of("pcap://os1.pcap"), error));
  EXPECT_EQ(error, "pcap://os1.pcap: cannot be sent to: only udp, tcp and serial are sinks");
}

TEST(Open, NoDescriptorOutlivesItsOwner) {
  auto open_fds = [] {
    int count = 0;
    for (int fd = 0; fd < 1024; ++fd)
      if (::fcntl(fd, F_GETFD) != -1) ++count;
    return count;
  };
  int before = open_fds();
  {
    PtyPair pair;
    std::string error;
    uint16_t port = free_port(SOCK_STREAM);
    std::string tcp = "tcp://127.0.0.1:" + std::to_string(port);
    auto a = open_source(spec_of("serial://" + pair.pty.slave_path), error);
    auto b = open_sink(spec_of(tcp), error);
    auto c = open_source(spec_of(tcp), error);
    auto d = open_source(spec_of("udp://127.0.0.1:" + std::to_string(free_port(SOCK_DGRAM))), error);
    auto e = open_source(spec_of("serial:///dev/null"), error);  // fails after opening: closed too
    ASSERT_TRUE(a && b && c && d && !e);
    EXPECT_NE(::fcntl(pair.pty.master_fd, F_GETFD) & FD_CLOEXEC, 0);
  }
  EXPECT_EQ(open_fds(), before);
}

// --- a device opened again after it failed (reopening_device.hpp) --------------------------

// Polls `device` (the run clock at now_ns) while `sink` sends probes, until one arrives; false
// when none does in 2 s.
bool heard_through(ReopeningDevice& device, ByteSink& sink, int64_t now_ns) {
  const uint8_t probe = 'x';
  for (int i = 0; i < 400; ++i) {
    sink.send(&probe, 1);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    Entries got;
    if (device.poll(now_ns, got, 1 << 16) && !got.empty()) return true;
  }
  return false;
}

// Polls until the device fails; false when it does not in 2 s.
bool fails(ReopeningDevice& device, int64_t now_ns) {
  for (int i = 0; i < 400; ++i) {
    Entries got;
    if (!device.poll(now_ns, got, 1 << 16)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return false;
}

// A receiver listening on a free TCP port (a GNSS receiver's), which can reboot: closed, then
// listening again on the same port.
struct Receiver {
  std::string name = "tcp://127.0.0.1:" + std::to_string(free_port(SOCK_STREAM));
  std::unique_ptr<ByteSink> sink = listen();
  std::unique_ptr<ByteSink> listen() const {
    std::string error;
    auto s = open_sink(spec_of(name), error);
    EXPECT_TRUE(s) << error;
    return s;
  }
};

// A receiver that reboots: its port closes, then listens again; the client is opened anew once
// the retry time has passed on the run's clock, not before, and reads again.
TEST(ReopeningDevice, ATcpReceiverThatComesBackIsReadAgain) {
  Receiver receiver;
  ASSERT_TRUE(receiver.sink);
  ReopeningDevice device(spec_of(receiver.name), 0.5);
  ASSERT_TRUE(heard_through(device, *receiver.sink, 0));
  EXPECT_GE(device.fd(), 0);

  receiver.sink.reset();  // the receiver reboots
  ASSERT_TRUE(fails(device, 1'000'000'000));
  EXPECT_EQ(device.error(), receiver.name + ": closed by the peer");
  EXPECT_EQ(device.fd(), -1);
  EXPECT_EQ(device.failures(), 1u);

  receiver.sink = receiver.listen();
  ASSERT_TRUE(receiver.sink);
  Entries none;
  EXPECT_FALSE(device.poll(1'400'000'000, none, 1 << 16));  // 0.4 s after the failure: not yet
  EXPECT_EQ(device.reopened(), 0u);
  ASSERT_TRUE(heard_through(device, *receiver.sink, 1'500'000'000));
  EXPECT_EQ(device.reopened(), 1u);
  EXPECT_EQ(device.error(), "");
  EXPECT_GE(device.fd(), 0);
}

TEST(ReopeningDevice, WithNoRetryAFailedDeviceStaysFailed) {
  Receiver receiver;
  ASSERT_TRUE(receiver.sink);
  ReopeningDevice device(spec_of(receiver.name), 0);
  ASSERT_TRUE(heard_through(device, *receiver.sink, 0));
  receiver.sink.reset();
  ASSERT_TRUE(fails(device, 0));
  receiver.sink = receiver.listen();
  ASSERT_TRUE(receiver.sink);
  Entries none;
  EXPECT_FALSE(device.poll(3'600'000'000'000, none, 1 << 16));
  EXPECT_EQ(device.reopened(), 0u);
  EXPECT_EQ(device.error(), receiver.name + ": closed by the peer");
}

TEST(ReopeningDevice, ADeviceThatCannotBeOpenedAtTheStartIsRefused) {
  EXPECT_THROW(ReopeningDevice(spec_of("serial:///dev/ttyBY_NONE"), 1.0), std::runtime_error);
}

TEST(ParseSource, ReopenIsOneSecondUnlessSaid) {
  EXPECT_EQ(spec_of("tcp://10.0.0.2:3001").reopen_s, 1.0);
  EXPECT_EQ(spec_of("tcp://10.0.0.2:3001?reopen=0").reopen_s, 0.0);
  EXPECT_EQ(spec_of("serial:///dev/ttyS0?baud=9600&reopen=2.5").reopen_s, 2.5);
}

}  // namespace
}  // namespace brickyard::drivers
