#pragma once
// What a replay node checks of a recording before the run starts, and the re-timing of its
// samples, framework-free. Each check returns why the recording cannot be replayed as asked (the
// plugin's error message), empty when it can.
#include "recording.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace brickyard::replay {

// Stamps are the recording run's clock: sim time from 0, or the epoch on the real clock. A
// recording replays on the clock it was made on (`recorded`: its "clock" metadata, empty when
// unknown), or with `retime` (retime_from_ns given) a real-clock one on the sim clock.
std::string clock_problem(const std::string& file, const std::string& recorded, bool sim_clock, bool retime);

// The recording has no topic `topic`: the message names those it has.
std::string missing_topic(const std::string& file, const Recording& rec, const std::string& topic);

// The topic holds another type than `want` (`replays`: this node's message type, named in the
// message), or the same type from another IDL definition (`want_hash`).
std::string type_problem(const std::string& file, const std::string& topic, const RecordedTopic& t, const std::string& want,
                         const std::string& want_hash, const std::string& replays);

// A sample's time on this run's clock: its recorded stamp, less `retime_from_ns` when that is not
// -1 (off); nothing for a sample from before it (the drive starts at 0).
std::optional<std::int64_t> retimed(std::int64_t stamp_ns, std::int64_t retime_from_ns);

}  // namespace brickyard::replay
