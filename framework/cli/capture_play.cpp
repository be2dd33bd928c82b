// `brickyard capture play FILE --to SINK`: a capture's bytes sent down a wire again, on the wall
// clock at the recorded pace: a pcap's UDP payloads one datagram each, a GNSS log's messages
// each at its log's time. A command-line tool, not a node: it sleeps, and a signal ends it.
#include "cli/capture.hpp"
#include "cli/capture_file.hpp"
#include "cli/capture_gnss.hpp"
#include "exec/run_types.hpp"  // g_interrupt
#include "graph/diagnostics.hpp"

#include "drivers/common/pcap_reader.hpp"
#include "drivers/io/byte_source.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <thread>

namespace brickyard::fw::cli {

namespace {

using Clock = std::chrono::steady_clock;
namespace dr = brickyard::drivers;

// A GNSS log's message goes out in pieces no larger than an Ethernet frame's UDP payload, so a
// datagram is never fragmented (the driver reads a stream in any chunking).
constexpr std::size_t kMaxPiece = 1472;

void on_signal(int) { g_interrupt = true; }

// One pass's pace: a record made t after the pass's first is due t / rate after the first went.
class WallPace {
 public:
  explicit WallPace(double rate) : rate_(rate) {}

  // Sleeps until `recorded_ns` is due, in slices of at most 50 ms so that a signal ends the wait
  // at once: false when interrupted.
  bool wait(std::int64_t recorded_ns) {
    if (!started_) started_ = true, first_ns_ = recorded_ns, start_ = Clock::now();
    if (rate_ <= 0) return !g_interrupt;
    // At most 1e9 s (31 years) ahead, so that a wild record time or a tiny rate stays a
    // duration the clock can hold (a wait so long ends by a signal anyway).
    const double delay_s = std::min(static_cast<double>(recorded_ns - first_ns_) * 1e-9 / rate_, 1e9);
    const auto due = start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(delay_s));
    while (!g_interrupt) {
      const auto now = Clock::now();
      if (now >= due) return true;
      std::this_thread::sleep_until(std::min(due, now + std::chrono::milliseconds(50)));
    }
    return false;
  }

 private:
  double rate_;
  bool started_ = false;
  std::int64_t first_ns_ = 0;  // the pass's first record's time, sent at start_
  Clock::time_point start_;
};

struct Player {
  dr::ByteSink& sink;
  double rate;
  std::uint64_t messages = 0, bytes = 0, passes = 0;

  bool send(const std::uint8_t* data, std::size_t size) {
    if (!sink.send(data, size)) return false;
    bytes += size;
    return true;
  }
};

// One pass of a pcap: each datagram to `port` (0: every one) at its capture time. False when
// interrupted or the sink failed.
bool play_pcap(const CaptureFile& f, std::uint16_t port, Player& p) {
  dr::PcapReader reader(f.bytes);
  WallPace pace(p.rate);
  while (auto d = reader.next()) {
    if (port && d->destination_port != port) continue;
    if (!pace.wait(d->time_ns) || !p.send(d->payload.data(), d->payload.size())) return false;
    ++p.messages;
  }
  return true;
}

// One pass of a GNSS log: each message's bytes at its time (one without a time right after the
// message before it).
bool play_gnss(const CaptureFile& f, const std::vector<GnssChunk>& chunks, Player& p) {
  WallPace pace(p.rate);
  std::optional<std::int64_t> last;
  std::size_t begin = 0;
  for (const GnssChunk& c : chunks) {
    if (c.time_ns) last = c.time_ns;
    if (last && !pace.wait(*last)) return false;
    if (g_interrupt) return false;
    for (std::size_t at = begin; at < c.end; at += kMaxPiece)
      if (!p.send(f.bytes.data() + at, std::min(kMaxPiece, c.end - at))) return false;
    begin = c.end;
    p.messages += c.message;
  }
  return true;
}

// What a pass will send, checked before anything is: none is bad input (exit 2).
std::vector<GnssChunk> what_to_send(const CaptureFile& f, const CaptureOptions& o) {
  if (f.kind == CaptureKind::gnss_log) {
    if (o.port) throw InvalidInput("--port", "selects a pcap's datagrams; " + f.path + " is a GNSS log");
    GnssLogInfo info = decode_gnss_log(f.bytes, true);
    if (info.counters.decoded == 0) throw InvalidInput(f.path, "no OEM7 log or NMEA sentence in it to pace the bytes by");
    return std::move(info.chunks);
  }
  dr::PcapReader reader(f.bytes);
  while (auto d = reader.next())
    if (!o.port || d->destination_port == *o.port) return {};
  throw InvalidInput(f.path, o.port ? "no UDP datagram to port " + std::to_string(*o.port) : "no UDP datagram");
}

// --to, checked before the capture is read (it may be large), opened after.
dr::SourceSpec parse_to(const std::string& to) {
  if (to.empty()) throw InvalidInput("capture play", "needs --to udp://HOST:PORT, where to send (nothing is sent unless asked)");
  dr::ParsedSource parsed = dr::parse_source(to);
  if (!parsed.spec) throw InvalidInput("--to", parsed.error);
  return std::move(*parsed.spec);
}

std::unique_ptr<dr::ByteSink> open_to(const dr::SourceSpec& spec) {
  std::string error;
  auto sink = dr::open_sink(spec, error);
  if (!sink) throw InvalidInput("--to", error);
  return sink;
}

}  // namespace

int capture_play(const CaptureOptions& o) {
  const dr::SourceSpec to = parse_to(o.to);
  const CaptureFile f = read_capture(o.file);
  const std::vector<GnssChunk> chunks = what_to_send(f, o);
  const auto sink = open_to(to);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  // Said once the signals are ours: from here a Ctrl-C ends the play cleanly, with its summary.
  char pace[64] = "full speed";
  if (o.rate > 0) std::snprintf(pace, sizeof pace, "%g x the recorded pace", o.rate);
  std::fprintf(stderr, "capture play: sending %s to %s at %s%s (Ctrl-C stops)\n", f.path.c_str(), o.to.c_str(), pace,
               o.loop ? ", looping" : "");
  Player p{*sink, o.rate};
  const auto start = Clock::now();
  bool ok = true;
  do {
    ok = f.kind == CaptureKind::pcap ? play_pcap(f, static_cast<std::uint16_t>(o.port.value_or(0)), p) : play_gnss(f, chunks, p);
    if (ok) ++p.passes;
  } while (ok && o.loop && !g_interrupt);
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  std::fprintf(stderr, "capture play: %llu %s (%llu bytes) of %s to %s, %llu whole pass%s in %.3f s; %llu bytes dropped (the sink's buffer full)%s\n",
               static_cast<unsigned long long>(p.messages), f.kind == CaptureKind::pcap ? "datagrams" : "messages",
               static_cast<unsigned long long>(p.bytes), f.path.c_str(), o.to.c_str(), static_cast<unsigned long long>(p.passes),
               p.passes == 1 ? "" : "es", wall, static_cast<unsigned long long>(sink->dropped()), g_interrupt ? " (interrupted)" : "");
  if (!ok && !g_interrupt) return std::fprintf(stderr, "error: %s\n", sink->error().c_str()), 1;
  return 0;
}

}  // namespace brickyard::fw::cli
