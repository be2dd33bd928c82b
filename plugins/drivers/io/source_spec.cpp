// parse_source: a driver's `source` string to a SourceSpec, or a message naming the part that is
// wrong. Nothing is resolved or opened here (HOST must be an IPv4 address: a name lookup could
// block, and would ask a DNS server outside the machine).
#include "byte_source.hpp"
#include "serial_settings.hpp"

#include <arpa/inet.h>

#include <array>
#include <charconv>
#include <cmath>
#include <utility>

namespace brickyard::drivers {
namespace {

using Params = std::vector<std::pair<std::string_view, std::string_view>>;

struct Scheme {
  std::string_view name;
  SourceSpec::Kind kind;
  std::string_view params;  // the parameters it takes, for messages and checks
};
constexpr std::array<Scheme, 5> kSchemes{{{"udp", SourceSpec::Kind::udp, "group, reopen"},
                                          {"tcp", SourceSpec::Kind::tcp, "reopen"},
                                          {"serial", SourceSpec::Kind::serial, "baud, framing, reopen"},
                                          {"file", SourceSpec::Kind::file, "rate"},
                                          {"pcap", SourceSpec::Kind::pcap, "rate, port"}}};

// Builds "source 'TEXT': WHAT".
class Refusal {
 public:
  explicit Refusal(std::string_view text) : text_(text) {}
  ParsedSource operator()(const std::string& what) const {
    return {std::nullopt, "source '" + std::string(text_) + "': " + what};
  }

 private:
  std::string_view text_;
};

bool takes_param(const Scheme& scheme, std::string_view key) {
  std::string_view list = scheme.params;
  while (!list.empty()) {
    size_t comma = list.find(", ");
    if (list.substr(0, comma) == key) return true;
    list = comma == std::string_view::npos ? std::string_view{} : list.substr(comma + 2);
  }
  return false;
}

// "a=1&b=2" into pairs; empty, or what is wrong with it.
std::string split_params(std::string_view query, const Scheme& scheme, Params& params) {
  while (!query.empty()) {
    size_t amp = query.find('&');
    std::string_view item = query.substr(0, amp);
    query = amp == std::string_view::npos ? std::string_view{} : query.substr(amp + 1);
    size_t eq = item.find('=');
    std::string_view key = item.substr(0, eq);
    if (key.empty()) return "empty parameter in the query";
    if (eq == std::string_view::npos || eq + 1 == item.size())
      return "parameter '" + std::string(key) + "' has no value";
    if (!takes_param(scheme, key)) {
      std::string known = scheme.params.empty() ? "none" : std::string(scheme.params);
      return "unknown parameter '" + std::string(key) + "' for " + std::string(scheme.name) + " (takes: " + known + ")";
    }
    for (const auto& [seen, value] : params)
      if (seen == key) return "parameter '" + std::string(key) + "' given twice";
    params.emplace_back(key, item.substr(eq + 1));
  }
  return {};
}

bool read_int(std::string_view text, long long& value) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end && !text.empty();
}

// A port 1..65535; empty, or what is wrong with it.
std::string read_port(std::string_view text, uint16_t& port) {
  long long value = 0;
  if (!read_int(text, value)) return "port '" + std::string(text) + "' is not a number";
  if (value < 1 || value > 65535) return "port " + std::string(text) + " out of 1..65535";
  port = static_cast<uint16_t>(value);
  return {};
}

bool is_ipv4(const std::string& text, in_addr& address) { return ::inet_pton(AF_INET, text.c_str(), &address) == 1; }

// HOST:PORT for udp and tcp; the port is checked first so a wrong one is named even beside a wrong host.
std::string read_endpoint(std::string_view target, SourceSpec& spec) {
  size_t colon = target.rfind(':');
  if (colon == std::string_view::npos) return "expected HOST:PORT, got '" + std::string(target) + "'";
  if (colon == 0) return "host missing before ':'";
  if (std::string error = read_port(target.substr(colon + 1), spec.port); !error.empty()) return error;
  spec.host = std::string(target.substr(0, colon));
  in_addr address{};
  if (!is_ipv4(spec.host, address))
    return "host '" + spec.host + "' is not an IPv4 address (names are not resolved)";
  return {};
}

std::string read_group(std::string_view text, SourceSpec& spec) {
  spec.group = std::string(text);
  in_addr address{};
  // 224.0.0.0/4 is IPv4's multicast range (RFC 5771).
  if (!is_ipv4(spec.group, address) || (ntohl(address.s_addr) >> 28) != 0xE)
    return "group '" + spec.group + "' is not an IPv4 multicast address (224.0.0.0 to 239.255.255.255)";
  return {};
}

std::string read_baud(std::string_view text, SourceSpec& spec) {
  long long value = 0;
  if (!read_int(text, value)) return "baud '" + std::string(text) + "' is not a number";
  if (value > 0 && value <= 921600 && serial_baud_supported(static_cast<int>(value))) {
    spec.baud = static_cast<int>(value);
    return {};
  }
  return "baud " + std::string(text) + " is not one of the POSIX rates (" + serial_bauds_listed() + ")";
}

std::string read_framing(std::string_view text, SourceSpec& spec) {
  if (!serial_framing_supported(text))
    return "framing '" + std::string(text) + "' is not one of " + serial_framings_listed();
  spec.framing = std::string(text);
  return {};
}

// A finite number, 0 or more, into `value` (`zero_means` for the message); empty, or what is wrong.
std::string read_nonnegative(std::string_view key, std::string_view text, const char* zero_means, double& value) {
  const char* end = text.data() + text.size();
  double read = 0;
  auto [ptr, ec] = std::from_chars(text.data(), end, read);
  if (ec != std::errc() || ptr != end || text.empty()) return std::string(key) + " '" + std::string(text) + "' is not a number";
  if (!std::isfinite(read) || read < 0)
    return std::string(key) + " " + std::string(text) + " must be finite and 0 (" + zero_means + ") or more";
  value = read;
  return {};
}

std::string read_path(std::string_view target, SourceSpec& spec) {
  if (target.empty()) return "path missing";
  spec.path = std::string(target);
  // serial:///dev/ttyUSB0: the third slash starts the path; "serial://dev/ttyUSB0" is a slip.
  if (spec.kind == SourceSpec::Kind::serial && target.front() != '/')
    return "path '" + spec.path + "' is not absolute (serial:///dev/ttyUSB0)";
  return {};
}

std::string read_param(std::string_view key, std::string_view value, SourceSpec& spec) {
  if (key == "group") return read_group(value, spec);
  if (key == "baud") return read_baud(value, spec);
  if (key == "framing") return read_framing(value, spec);
  if (key == "rate") return read_nonnegative(key, value, "as fast as read", spec.rate);
  if (key == "reopen") return read_nonnegative(key, value, "never", spec.reopen_s);
  std::string error = read_port(value, spec.port);  // pcap's filter, the only other key taken
  return error.empty() ? error : "filter " + error;
}

}  // namespace

ParsedSource parse_source(std::string_view text) {
  Refusal refuse(text);
  size_t sep = text.find("://");
  if (sep == std::string_view::npos) return refuse("expected SCHEME://..., SCHEME one of udp, tcp, serial, file, pcap");
  std::string_view name = text.substr(0, sep);
  const Scheme* scheme = nullptr;
  for (const Scheme& s : kSchemes)
    if (s.name == name) scheme = &s;
  if (scheme == nullptr) return refuse("unknown scheme '" + std::string(name) + "' (udp, tcp, serial, file, pcap)");
  SourceSpec spec;
  spec.kind = scheme->kind;
  spec.text = std::string(text);
  std::string_view rest = text.substr(sep + 3);
  size_t question = rest.find('?');
  std::string_view target = rest.substr(0, question);
  Params params;
  if (question != std::string_view::npos)
    if (std::string error = split_params(rest.substr(question + 1), *scheme, params); !error.empty()) return refuse(error);
  bool network = spec.kind == SourceSpec::Kind::udp || spec.kind == SourceSpec::Kind::tcp;
  std::string error = network ? read_endpoint(target, spec) : read_path(target, spec);
  if (!error.empty()) return refuse(error);
  for (const auto& [key, value] : params)
    if (error = read_param(key, value, spec); !error.empty()) return refuse(error);
  return {std::move(spec), {}};
}

}  // namespace brickyard::drivers
