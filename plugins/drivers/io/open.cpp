// open_source and open_sink: a parsed spec to its transport. Replays (file://, pcap://) are not
// opened here: the plugin reads them at the pace of the run's clock, which a transport never reads.
#include "transports.hpp"

#include <exception>

namespace brickyard::drivers {
namespace {

std::unique_ptr<ByteSource> open_live_source(const SourceSpec& spec, const std::string& name, std::string& error) {
  switch (spec.kind) {
    case SourceSpec::Kind::udp: return open_udp_source(spec, name, error);
    case SourceSpec::Kind::tcp: return open_tcp_source(spec, name, error);
    case SourceSpec::Kind::serial: return open_serial_source(spec, name, error);
    case SourceSpec::Kind::file:
    case SourceSpec::Kind::pcap: break;
  }
  error = name + ": not a live device: the driver replays it, paced by the run's clock";
  return nullptr;
}

std::unique_ptr<ByteSink> open_live_sink(const SourceSpec& spec, const std::string& name, std::string& error) {
  switch (spec.kind) {
    case SourceSpec::Kind::udp: return open_udp_sink(spec, name, error);
    case SourceSpec::Kind::tcp: return open_tcp_sink(spec, name, error);
    case SourceSpec::Kind::serial: return open_serial_sink(spec, name, error);
    case SourceSpec::Kind::file:
    case SourceSpec::Kind::pcap: break;
  }
  error = name + ": cannot be sent to: only udp, tcp and serial are sinks";
  return nullptr;
}

// Only allocation can throw in an opener; it is reported like any failure to open, so no
// exception reaches the plugin.
template <typename Opener>
auto guarded(Opener opener, const SourceSpec& spec, std::string& error) {
  error.clear();
  try {
    return opener(spec, device_name(spec), error);
  } catch (const std::exception& e) {
    error = "cannot open a device: " + std::string(e.what());
    return decltype(opener(spec, std::string(), error))();
  }
}

}  // namespace

std::unique_ptr<ByteSource> open_source(const SourceSpec& spec, std::string& error) {
  return guarded(open_live_source, spec, error);
}

std::unique_ptr<ByteSink> open_sink(const SourceSpec& spec, std::string& error) {
  return guarded(open_live_sink, spec, error);
}

}  // namespace brickyard::drivers
