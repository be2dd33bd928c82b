// brickyard-can: a recorded bus, out of a recording and back onto a bus.
//   brickyard-can candump RECORDING.mcap --out FILE.log [--topic NODE.PORT] [--interface NAME]
//   brickyard-can play FILE.log --to udp://HOST:PORT [--rate R]
// `candump` writes the frames of a vehicle interface's `frames` output (CanFrames: every frame it
// wrote and read) as a candump log (can-utils' `candump -L`, what canplayer replays onto a real bus),
// in their order, stamped with the run's clock; every CanFrames topic of the recording, or the one
// named. `play` sends a candump log's frames as cannelloni datagrams to a udp:// bus (the vehicle
// interface's, the simulated drive-by-wire's, cannelloni's bridge to a real bus), at the log's pace
// times R (0: at once), the frames of one timestamp in one datagram where they fit.
// docs/vehicle-interface.md, "Recording the bus". Bad input: a message naming it, exit 2.
#include <brickyard/msgs/CanFrames.h>

#include "mcap/mcap_reader.hpp"
#include "vehicle_interface/bus/can_bus.hpp"
#include "vehicle_interface/common/candump_log.hpp"

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace brickyard;
using namespace brickyard::vehicle_interface;

namespace {

constexpr const char* kType = "brickyard::msgs::CanFrames";

struct BadInput : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void usage(const std::string& why) {
  std::fprintf(stderr,
               "brickyard-can: %s\nusage: brickyard-can candump RECORDING.mcap --out FILE.log [--topic NODE.PORT] [--interface NAME]\n"
               "       brickyard-can play FILE.log --to udp://HOST:PORT [--rate R]\n",
               why.c_str());
  std::exit(2);
}

// "--name value" options after the one positional argument.
std::map<std::string, std::string> options(int argc, char** argv, const std::vector<std::string>& known) {
  std::map<std::string, std::string> out;
  for (int i = 3; i < argc; i += 2) {
    const std::string name = argv[i];
    bool ok = false;
    for (const std::string& k : known) ok = ok || name == k;
    if (!ok) usage(name + ": unknown option");
    if (i + 1 >= argc) usage(name + ": needs a value");
    out[name] = argv[i + 1];
  }
  return out;
}

msgs::CanFrames decode(const mcap::MessageView& m, const std::string& topic) {
  std::vector<char> bytes(m.data, m.data + m.size);  // fastcdr reads through a mutable buffer
  eprosima::fastcdr::FastBuffer buffer(bytes.data(), bytes.size());
  eprosima::fastcdr::Cdr cdr(buffer, eprosima::fastcdr::Cdr::DEFAULT_ENDIAN, eprosima::fastcdr::Cdr::DDS_CDR);
  msgs::CanFrames out;
  try {
    cdr.read_encapsulation();
    out.deserialize(cdr);
  } catch (const std::exception& e) {  // fastcdr's errors, and a length in the bytes too large to allocate
    throw BadInput(topic + ": message " + std::to_string(m.sequence) + " does not decode as CanFrames (" + e.what() + ")");
  }
  return out;
}

CandumpRecord record_of(const msgs::CanFrameRecord& r, const std::string& interface) {
  CandumpRecord c;
  const std::int64_t ns = r.stamp_ns() < 0 ? 0 : r.stamp_ns();
  c.seconds = static_cast<uint64_t>(ns / 1'000'000'000);
  c.microseconds = static_cast<uint32_t>(ns % 1'000'000'000 / 1000);
  c.interface = interface;
  c.frame.id = r.id(), c.frame.extended = r.extended(), c.frame.remote = r.remote(), c.frame.fd = r.fd(), c.frame.fd_flags = r.fd_flags();
  c.frame.length = static_cast<uint8_t>(std::min<std::size_t>(r.data().size(), kFdMaxBytes));
  std::copy(r.data().begin(), r.data().begin() + c.frame.length, c.frame.data.begin());
  if (std::string why = frame_problem(c.frame); !why.empty()) throw BadInput("a recorded frame of id " + std::to_string(r.id()) + ": " + why);
  return c;
}

int candump(int argc, char** argv) {
  const auto o = options(argc, argv, {"--out", "--topic", "--interface"});
  if (!o.count("--out")) usage("candump: --out FILE.log is required");
  const std::string interface = o.count("--interface") ? o.at("--interface") : "can0";
  if (interface.empty() || interface.size() > 15 || interface.find_first_of(" \t\n()#") != std::string::npos)
    usage("--interface '" + interface + "': a name of 1 to 15 characters without spaces, '(', ')' or '#'");
  mcap::Reader reader(argv[2]);
  std::set<std::uint16_t> channels;
  for (const auto& [id, c] : reader.channels()) {
    const auto schema = reader.schemas().find(c.schema);
    const bool wanted = o.count("--topic") ? c.topic == o.at("--topic") : schema != reader.schemas().end() && schema->second.name == kType;
    if (wanted && (schema == reader.schemas().end() || schema->second.name != kType))
      throw BadInput(std::string(argv[2]) + ": topic " + c.topic + " holds " + (schema == reader.schemas().end() ? "no schema" : schema->second.name) + ", not CanFrames");
    if (wanted) channels.insert(id);
  }
  if (channels.empty())
    throw BadInput(std::string(argv[2]) + (o.count("--topic") ? ": no topic " + o.at("--topic") : ": no CanFrames topic (a vehicle interface's frames output)"));
  std::vector<CandumpRecord> records;
  reader.read([&](const mcap::MessageView& m) {
    const msgs::CanFrames f = decode(m, reader.channels().at(m.channel).topic);
    for (const msgs::CanFrameRecord& r : f.frames()) records.push_back(record_of(r, interface));
  }, &channels);
  std::string error;
  if (!save_candump_file(o.at("--out"), records, &error)) throw BadInput(error);
  std::printf("%zu frames from %zu topic(s) of %s into %s%s\n", records.size(), channels.size(), argv[2], o.at("--out").c_str(),
              reader.damage() ? (" (the recording is damaged: " + reader.damage()->what + ")").c_str() : "");
  return 0;
}

int play(int argc, char** argv) {
  const auto o = options(argc, argv, {"--to", "--rate"});
  if (!o.count("--to")) usage("play: --to udp://HOST:PORT is required");
  double rate = 1;
  if (o.count("--rate")) {
    char* end = nullptr;
    rate = std::strtod(o.at("--rate").c_str(), &end);
    if (end == o.at("--rate").c_str() || *end || !(rate == 0 || (rate >= 0.001 && rate <= 1e6)))
      usage("--rate " + o.at("--rate") + ": 0 (at once) or 0.001 to 1e6");
  }
  std::string error;
  const std::optional<drivers::SourceSpec> to = parse_udp_address(o.at("--to"), error);
  if (!to) throw BadInput("--to: " + error);
  const CandumpLog log = load_candump_file(argv[2]);
  if (!log.errors.empty()) {
    const CandumpLineError& e = log.errors.front();  // line 0: the file itself
    throw BadInput(e.line == 0 ? e.what : std::string(argv[2]) + ": " + e.text() + " (bad lines: " + std::to_string(log.bad_lines) + ")");
  }
  std::unique_ptr<CanBus> bus = open_udp_sender(*to, error);
  if (!bus) throw BadInput("--to: " + error);
  const auto start = std::chrono::steady_clock::now();
  const auto stamp_us = [](const CandumpRecord& r) { return static_cast<double>(r.seconds) * 1e6 + r.microseconds; };
  std::size_t sent = 0;
  for (std::size_t i = 0; i < log.records.size();) {
    std::vector<CanFrame> batch;
    const double at = stamp_us(log.records[i]);
    for (; i < log.records.size() && stamp_us(log.records[i]) == at; ++i) batch.push_back(log.records[i].frame);
    if (rate > 0) std::this_thread::sleep_until(start + std::chrono::microseconds(static_cast<long long>((at - stamp_us(log.records[0])) / rate)));
    if (!bus->send(batch)) throw BadInput("--to " + o.at("--to") + ": " + bus->error());
    sent += batch.size();
  }
  std::printf("%zu frames of %s sent to %s (%llu dropped by the kernel)\n", sent, argv[2], o.at("--to").c_str(),
              static_cast<unsigned long long>(bus->counts().frames_dropped));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) usage("needs a command and a file");
  const std::string command = argv[1];
  try {
    if (command == "candump") return candump(argc, argv);
    if (command == "play") return play(argc, argv);
    usage("'" + command + "': the commands are candump and play");
  } catch (const BadInput& e) {
    std::fprintf(stderr, "brickyard-can: %s\n", e.what());
  } catch (const mcap::ReadError& e) {
    std::fprintf(stderr, "brickyard-can: %s\n", e.what());
  }
  return 2;
}
