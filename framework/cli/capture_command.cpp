// `brickyard capture info | play FILE`: the command line as CaptureOptions (cli/capture.hpp), and
// info itself: the capture read, decoded and printed.
#include "cli/capture.hpp"
#include "cli/capture_file.hpp"
#include "cli/capture_report.hpp"
#include "cli/command_table.hpp"
#include "graph/diagnostics.hpp"

namespace brickyard::fw::cli {

namespace {

constexpr const char* kVerbs = "(brickyard capture info FILE [--metadata OUSTER.json] [--json] | play FILE --to udp://HOST:PORT)";

void print_pcap(const CaptureOptions& o, const CaptureFile& f) {
  std::optional<OusterInfo> ouster;
  if (!o.metadata.empty()) {
    ouster.emplace();
    ouster->metadata_path = o.metadata;
    ouster->metadata = read_ouster_metadata(o.metadata);
    ouster->port = static_cast<std::uint16_t>(o.port.value_or(ouster->metadata.udp_port_lidar));
  }
  const PcapInfo info = tally_pcap(f.bytes, std::move(ouster));
  if (o.json) print_pcap_json(f.path, f.bytes.size(), info);
  else print_pcap_text(f.path, f.bytes.size(), info);
}

}  // namespace

int capture_info(const CaptureOptions& o) {
  const CaptureFile f = read_capture(o.file);
  if (f.kind == CaptureKind::pcap) {
    print_pcap(o, f);
    return 0;
  }
  if (!o.metadata.empty()) throw InvalidInput("--metadata", "decodes an Ouster pcap's packets; " + f.path + " is a GNSS log");
  const GnssLogInfo info = decode_gnss_log(f.bytes, false);
  if (o.json) print_gnss_json(f.path, f.bytes.size(), info);
  else print_gnss_text(f.path, f.bytes.size(), info);
  return 0;
}

int cmd_capture(const Args& a) {
  if (a.target != "info" && a.target != "play")
    usage_error(a.target.empty() ? "capture" : "capture " + a.target,
                std::string(a.target.empty() ? "needs a command " : "unknown capture command ") + kVerbs);
  if (a.more.size() != 1) usage_error("capture " + a.target, std::string("needs one capture, a pcap or a GNSS log ") + kVerbs);
  CaptureOptions o;
  o.file = a.more[0];
  o.metadata = a.metadata;
  o.to = a.to;
  o.port = a.port;
  o.rate = a.rate;
  o.loop = a.loop;
  o.json = a.json;
  return a.target == "info" ? capture_info(o) : capture_play(o);
}

}  // namespace brickyard::fw::cli
