// libFuzzer harness: a track (or racing line) file's text through the reader and into the
// track's geometry, as the map, the world and brickyard-plan load one. Bad input must end in
// TrackFileError / invalid_argument naming the line or the reason.
#include "track/centre_line.hpp"
#include "track/track.hpp"

#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    brickyard::track::TrackGeometry g;
    g.name = "fuzz.csv";
    g.line = brickyard::track::parse_centerline_csv(in, "fuzz.csv");
    const brickyard::track::Track t(std::move(g));
    (void)t.project(0, 0);
  } catch (const std::exception&) {  // TrackFileError, invalid_argument: named refusals
  }
  return 0;
}
