#include "replay_checks.hpp"

namespace brickyard::replay {

std::string clock_problem(const std::string& file, const std::string& recorded, bool sim_clock, bool retime) {
  const std::string made_on = recorded.empty() ? "unknown" : recorded;
  const std::string run_on = sim_clock ? "sim" : "real";
  if (retime && !(recorded == "real" && sim_clock))
    return "parameter 'retime_from_ns': re-times a real-clock recording onto the sim clock; " + file + " was made on the " + made_on +
           " clock and this run is on the " + run_on + " clock";
  if (!retime && recorded != run_on)
    return "recording " + file + " was made on the " + made_on + " clock, this run is on the " + run_on +
           " clock: its samples' times would not line up";
  return {};
}

std::string missing_topic(const std::string& file, const Recording& rec, const std::string& topic) {
  std::string have;
  for (const auto& x : rec.topics()) have += (have.empty() ? "" : ", ") + x.name;
  return "recording " + file + " has no topic '" + topic + "' (it has: " + have + ")";
}

std::string type_problem(const std::string& file, const std::string& topic, const RecordedTopic& t, const std::string& want,
                         const std::string& want_hash, const std::string& replays) {
  if (t.type != want)
    return "recording " + file + ": topic '" + topic + "' holds " + t.type + ", this node replays " + replays +
           " (use the replay plugin of that type)";
  if (t.type_hash != want_hash)
    return "recording " + file + ": topic '" + topic + "' was recorded with another definition of " + t.type + " (IDL hash " + t.type_hash +
           ", this build " + want_hash + ")";
  return {};
}

std::optional<std::int64_t> retimed(std::int64_t stamp_ns, std::int64_t retime_from_ns) {
  if (retime_from_ns < 0) return stamp_ns;
  if (stamp_ns < retime_from_ns) return std::nullopt;
  return stamp_ns - retime_from_ns;
}

}  // namespace brickyard::replay
