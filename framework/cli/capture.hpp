#pragma once
// `brickyard capture info | play FILE`: a sensor's recording (a pcap of UDP packets, or a GNSS
// receiver's log of OEM7 logs or NMEA sentences) inspected with the drivers' own decoders, or
// sent down a wire again at its recorded pace (docs/drivers.md, "Captures: info and play").
// Bad input throws InvalidInput naming the culprit (exit 2).
#include <optional>
#include <string>

namespace brickyard::fw::cli {

struct CaptureOptions {
  std::string file;
  std::string metadata;         // info: an Ouster metadata JSON, to decode the lidar port's packets
  std::string to;               // play: the sink (udp://HOST:PORT, tcp://, serial://)
  std::optional<int> port;      // a pcap's UDP destination port (info: the lidar's; play: the only one sent)
  double rate = 1.0;            // play: times the recorded pace; 0 as fast as possible
  bool loop = false, json = false;
};

// Prints what FILE holds (text, or JSON with `json`): 0.
int capture_info(const CaptureOptions& o);
// Sends FILE to `to` at its pace until it ends (or, with `loop`, until SIGINT/SIGTERM): 0; 1 when
// the sink fails on the way.
int capture_play(const CaptureOptions& o);

}  // namespace brickyard::fw::cli
