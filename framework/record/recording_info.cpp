#include "record/recording_info.hpp"

#include "io/bounded_read.hpp"
#include "mcap/mcap_format.hpp"
#include "mcap/mcap_reader.hpp"
#include "mcap/ros2_profile.hpp"

#include <sqlite3.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <utility>
#include <map>
#include <memory>
#include <stdexcept>

namespace brickyard::fw {

namespace {

// A channel's wire and type as we name them, whichever profile the file was recorded in (ours, or
// a ROS 2 bag's: mcap/ros2_profile.hpp).
std::pair<std::string, std::string> recorded_names(const mcap::Reader& r, const mcap::ChannelInfo& c) {
  const auto sc = r.schemas().find(c.schema);
  if (sc == r.schemas().end()) return {c.topic, ""};
  return mcap::brickyard_names(c.topic, sc->second.name, sc->second.encoding);
}

// An open read-only database, closed however the reading ends.
struct Db {
  sqlite3* db = nullptr;
  ~Db() { sqlite3_close(db); }
};

[[noreturn]] void fail(sqlite3* db, const std::string& what) {
  throw std::runtime_error(what + (db ? std::string(": ") + sqlite3_errmsg(db) : std::string()));
}

// Runs sql, calling row(stmt) for each row.
template <class Row> void query(sqlite3* db, const char* sql, Row&& row) {
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v2(db, sql, -1, &st, nullptr) != SQLITE_OK) fail(db, "not a readable recording");
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) row(st);
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) fail(db, "not a readable recording");
}

std::string text(sqlite3_stmt* st, int col) {
  const unsigned char* t = sqlite3_column_text(st, col);
  return t ? reinterpret_cast<const char*>(t) : "";
}

// The recording opened read-only, checked to be one.
void open_recording(const std::string& path, Db& d) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error("no such file");
  if (sqlite3_open_v2(path.c_str(), &d.db, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) fail(d.db, "cannot open");
  int ours = 0;
  query(d.db, "SELECT name FROM sqlite_master WHERE type = 'table' AND name IN ('metadata', 'topics', 'messages')",
        [&](sqlite3_stmt*) { ++ours; });
  if (ours != 3) throw std::runtime_error("not a recording (no metadata, topics and messages tables: brickyard run --record FILE)");
  // A stamp is the run's clock at publication, in whole nanoseconds, never before the epoch (a
  // row stamped INT64_MIN showed a span of -9223372036.855 s).
  std::int64_t bad = 0, first_id = 0;
  query(d.db, "SELECT count(*), coalesce(min(id), 0) FROM messages WHERE typeof(timestamp) != 'integer' OR timestamp < 0",
        [&](sqlite3_stmt* st) { bad = sqlite3_column_int64(st, 0), first_id = sqlite3_column_int64(st, 1); });
  if (bad > 0)
    throw std::runtime_error(std::to_string(bad) + " messages stamped with no time (negative, or not whole nanoseconds), the first message " +
                             std::to_string(first_id));
}

}  // namespace

bool is_mcap_file(const std::string& path) {
  // A FIFO would hold the read below (and SQLite's) until a writer came; a device may never end.
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw std::runtime_error("no such file");
  std::string why;
  if (!brickyard::io::is_regular_readable(path, why)) throw std::runtime_error(why.substr(std::min(why.size(), path.size() + 2)));
  char head[sizeof mcap::kMagic] = {};
  std::ifstream(path, std::ios::binary).read(head, sizeof head);
  return std::memcmp(head, mcap::kMagic, sizeof head) == 0;
}

void read_mcap_recording(const std::string& path, RecordingInfo& info, std::vector<TopicStats>& topics) {
  std::unique_ptr<mcap::Reader> r;
  try {
    r = std::make_unique<mcap::Reader>(path);
  } catch (const mcap::ReadError& e) {
    const std::string what = e.what();
    throw std::runtime_error(what.rfind(path + ": ", 0) == 0 ? what.substr(path.size() + 2) : what);
  }
  const auto m = r->metadata().find("brickyard");
  if (m == r->metadata().end() || !m->second.count("clock"))
    throw std::runtime_error("an MCAP file, but not a brickyard recording (no 'brickyard' metadata with its clock)");
  info = {};
  info.clock = m->second.at("clock");
  topics.clear();
  for (const auto& [id, c] : r->channels()) {
    // A stamp is the run's clock in nanoseconds, an int64 as SQLite's: one past 2^63 - 1 would
    // read as a time before the epoch (a span of -9223372036.855 s).
    if (c.messages && c.last > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      throw std::runtime_error("channel '" + c.topic + "' has a message stamped " + std::to_string(c.last) + " ns: past any run's clock (2^63 ns)");
    const auto [topic, type] = recorded_names(*r, c);
    info.topics.emplace_back(topic, type);
    topics.push_back({topic, type, c.messages, c.bytes, static_cast<std::int64_t>(c.first), static_cast<std::int64_t>(c.last)});
    info.messages += c.messages;
    if (c.messages) info.last_ns = std::max(info.last_ns, static_cast<std::int64_t>(c.last));
  }
  if (const mcap::Damage* d = r->damage()) info.damage = "damaged at byte " + std::to_string(d->offset) + ": " + d->what;
}

void for_each_sample(const std::string& path, const std::function<void(const std::string& topic, const std::string& type, std::int64_t stamp_ns,
                                                                     const unsigned char* data, std::size_t size)>& f) {
  if (is_mcap_file(path)) {
    std::unique_ptr<mcap::Reader> r;
    try {
      r = std::make_unique<mcap::Reader>(path);
    } catch (const mcap::ReadError& e) {
      throw std::runtime_error(e.what());
    }
    std::map<std::uint16_t, std::pair<std::string, std::string>> names;
    for (const auto& [id, c] : r->channels()) names[id] = recorded_names(*r, c);
    r->read([&](const mcap::MessageView& m) {
      const auto& [topic, type] = names[m.channel];
      f(topic, type, static_cast<std::int64_t>(m.log_time), m.data, m.size);
    });
    if (const mcap::Damage* d = r->damage()) throw std::runtime_error("damaged at byte " + std::to_string(d->offset) + ": " + d->what);
    return;
  }
  Db d;
  open_recording(path, d);
  std::map<std::int64_t, std::pair<std::string, std::string>> names;
  query(d.db, "SELECT id, name, type FROM topics", [&](sqlite3_stmt* st) { names[sqlite3_column_int64(st, 0)] = {text(st, 1), text(st, 2)}; });
  query(d.db, "SELECT topic_id, timestamp, data FROM messages ORDER BY id", [&](sqlite3_stmt* st) {
    const auto& [topic, type] = names[sqlite3_column_int64(st, 0)];
    f(topic, type, sqlite3_column_int64(st, 1), static_cast<const unsigned char*>(sqlite3_column_blob(st, 2)),
      static_cast<std::size_t>(sqlite3_column_bytes(st, 2)));
  });
}

RecordingInfo read_recording_info(const std::string& path) {
  if (is_mcap_file(path)) {
    RecordingInfo info;
    std::vector<TopicStats> topics;
    read_mcap_recording(path, info, topics);
    return info;
  }
  Db d;
  open_recording(path, d);
  RecordingInfo info;
  query(d.db, "SELECT value FROM metadata WHERE key = 'clock'", [&](sqlite3_stmt* st) { info.clock = text(st, 0); });
  query(d.db, "SELECT name, type FROM topics ORDER BY id", [&](sqlite3_stmt* st) { info.topics.emplace_back(text(st, 0), text(st, 1)); });
  // Ids are the publication order and stamps the run's clock at publication: the last row is the
  // last sample (read by rowid, not by scanning gigabytes of clouds).
  query(d.db, "SELECT id, timestamp FROM messages ORDER BY id DESC LIMIT 1", [&](sqlite3_stmt* st) {
    info.messages = static_cast<std::uint64_t>(sqlite3_column_int64(st, 0));
    info.last_ns = sqlite3_column_int64(st, 1);
  });
  return info;
}

std::vector<TopicStats> read_topic_stats(const std::string& path) {
  if (is_mcap_file(path)) {
    RecordingInfo info;
    std::vector<TopicStats> topics;
    read_mcap_recording(path, info, topics);
    return topics;
  }
  Db d;
  open_recording(path, d);
  std::vector<TopicStats> out;
  query(d.db,
        "SELECT t.name, t.type, count(m.id), coalesce(sum(length(m.data)), 0), coalesce(min(m.timestamp), 0), "
        "coalesce(max(m.timestamp), 0) FROM topics t LEFT JOIN messages m ON m.topic_id = t.id GROUP BY t.id ORDER BY t.id",
        [&](sqlite3_stmt* st) {
          TopicStats s;
          s.name = text(st, 0);
          s.type = text(st, 1);
          s.count = static_cast<std::uint64_t>(sqlite3_column_int64(st, 2));
          s.bytes = static_cast<std::uint64_t>(sqlite3_column_int64(st, 3));
          s.first_ns = sqlite3_column_int64(st, 4);
          s.last_ns = sqlite3_column_int64(st, 5);
          out.push_back(std::move(s));
        });
  return out;
}

}  // namespace brickyard::fw
