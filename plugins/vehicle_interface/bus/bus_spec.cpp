#include "can_bus.hpp"

#include <net/if.h>

namespace brickyard::vehicle_interface {

namespace {

// Linux's interface names: 1 to IFNAMSIZ - 1 bytes, no '/', no white space, not "." or "..".
std::string interface_problem(const std::string& name) {
  if (name.empty()) return "no interface named";
  if (name.size() >= IFNAMSIZ) return "interface name over " + std::to_string(IFNAMSIZ - 1) + " characters";
  if (name == "." || name == "..") return "'" + name + "' is no interface name";
  for (char c : name)
    if (c == '/' || c == ':' || c == '?' || static_cast<unsigned char>(c) <= ' ') return "'" + name + "' is no interface name";
  return "";
}

std::optional<drivers::SourceSpec> udp_spec(const std::string& text, std::string& error) {
  drivers::ParsedSource p = drivers::parse_source(text);
  if (!p.spec) {
    error = p.error;
    return std::nullopt;
  }
  if (p.spec->kind != drivers::SourceSpec::Kind::udp) {
    error = "'" + text + "': a bus is can://IFNAME, or udp://HOST:PORT with send_to udp://HOST:PORT";
    return std::nullopt;
  }
  return p.spec;
}

}  // namespace

std::optional<drivers::SourceSpec> parse_udp_address(const std::string& text, std::string& error) { return udp_spec(text, error); }

std::optional<BusSpec> parse_bus(const std::string& bus, const std::string& send_to, std::string& error, std::string& param) {
  BusSpec spec;
  spec.text = bus;
  param = "bus";
  if (bus.rfind("can://", 0) == 0) {
    spec.kind = BusSpec::Kind::socketcan;
    spec.interface = bus.substr(6);
    if (std::string why = interface_problem(spec.interface); !why.empty()) {
      error = "'" + bus + "': " + why;
      return std::nullopt;
    }
    if (!send_to.empty()) {
      param = "send_to";
      error = "a can:// bus sends on its interface; send_to is for udp:// only";
      return std::nullopt;
    }
    return spec;
  }
  std::optional<drivers::SourceSpec> listen = udp_spec(bus, error);
  if (!listen) return std::nullopt;
  param = "send_to";
  if (send_to.empty()) {
    error = "a udp:// bus needs send_to, udp://HOST:PORT (where the frames go)";
    return std::nullopt;
  }
  std::optional<drivers::SourceSpec> to = udp_spec(send_to, error);
  if (!to) return std::nullopt;
  spec.listen = *listen;
  spec.send_to = *to;
  return spec;
}

std::unique_ptr<CanBus> open_bus(const BusSpec& spec, std::string& error) {
  return spec.kind == BusSpec::Kind::socketcan ? open_socketcan_bus(spec, error) : open_udp_bus(spec, error);
}

}  // namespace brickyard::vehicle_interface
