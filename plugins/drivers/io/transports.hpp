#pragma once
// The transports behind open_source and open_sink, one file each (udp.cpp, tcp.cpp, serial.cpp,
// pty.cpp), and the two pieces they share: a stream read without blocking (tcp, serial) and a
// descriptor written without blocking (a tty, a pty's master). Each opener takes a parsed spec and
// the device's name for messages; on failure it returns null and sets `error` to
// "NAME: WHAT: OS error".
#include "byte_source.hpp"
#include "fd.hpp"

#include <netinet/in.h>

namespace brickyard::drivers {

std::unique_ptr<ByteSource> open_udp_source(const SourceSpec& spec, const std::string& name, std::string& error);
std::unique_ptr<ByteSink> open_udp_sink(const SourceSpec& spec, const std::string& name, std::string& error);
std::unique_ptr<ByteSource> open_tcp_source(const SourceSpec& spec, const std::string& name, std::string& error);
std::unique_ptr<ByteSink> open_tcp_sink(const SourceSpec& spec, const std::string& name, std::string& error);
std::unique_ptr<ByteSource> open_serial_source(const SourceSpec& spec, const std::string& name, std::string& error);
std::unique_ptr<ByteSink> open_serial_sink(const SourceSpec& spec, const std::string& name, std::string& error);

// How a stream's end reads in messages: a TCP peer closes, a serial line hangs up.
struct StreamWords {
  const char* ended;   // read returned 0
  const char* failed;  // read returned an error
};
// A non-blocking stream descriptor (a connected or connecting socket, a tty) as a ByteSource.
std::unique_ptr<ByteSource> make_stream_source(UniqueFd fd, std::string name, StreamWords words);
// A non-blocking descriptor (a tty, a pty's master) written as a ByteSink.
std::unique_ptr<ByteSink> make_fd_sink(UniqueFd fd, std::string name);

// A socket's IPv4 address for HOST:PORT; false if HOST is not an IPv4 address (a spec built in
// code, not by parse_source), so nothing is ever sent to or bound on an address it did not name.
bool ipv4_address(const std::string& host, uint16_t port, sockaddr_in& address);
// A non-blocking, close-on-exec IPv4 socket of `type` (SOCK_DGRAM, SOCK_STREAM), or an invalid one with errno set.
UniqueFd ipv4_socket(int type);
// Both: the address of HOST:PORT and a socket of `type` for it, or an invalid one with `error`
// naming the device and why (the host no IPv4 address, no socket to be had).
UniqueFd ipv4_socket_for(const std::string& host, uint16_t port, int type, const std::string& name, sockaddr_in& address,
                         std::string& error);

}  // namespace brickyard::drivers
