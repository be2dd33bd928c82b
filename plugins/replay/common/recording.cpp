#include "recording.hpp"

#include "mcap/mcap_format.hpp"
#include "mcap/mcap_reader.hpp"
#include "mcap/ros2_profile.hpp"

#include <sqlite3.h>

#include <cstring>
#include <filesystem>
#include <fstream>

namespace brickyard::replay {

Recording::Recording(const std::string& path) : path_(path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw RecordingError(path + ": no such recording");
  char head[sizeof mcap::kMagic] = {};
  std::ifstream(path, std::ios::binary).read(head, sizeof head);
  if (std::memcmp(head, mcap::kMagic, sizeof head) == 0) {
    try {
      mcap_ = std::make_unique<mcap::Reader>(path);
    } catch (const mcap::ReadError& e) {
      throw RecordingError(e.what());
    }
    if (const mcap::Damage* d = mcap_->damage())
      throw RecordingError(path + ": damaged at byte " + std::to_string(d->offset) + ": " + d->what);
    for (const auto& [id, c] : mcap_->channels()) {
      const auto sc = mcap_->schemas().find(c.schema);
      const auto hash = c.metadata.find("type_hash");
      const bool schema = sc != mcap_->schemas().end();
      // Named as we name them, in either profile (a ROS 2 bag's: mcap/ros2_profile.hpp).
      const auto [topic, type] = mcap::brickyard_names(c.topic, schema ? sc->second.name : "", schema ? sc->second.encoding : "");
      topics_.push_back({id, topic, type, hash == c.metadata.end() ? "" : hash->second, schema ? sc->second.data : ""});
    }
    return;
  }
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) fail("cannot open");
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT id, name, type, type_hash, idl FROM topics ORDER BY id", -1, &st, nullptr) != SQLITE_OK)
    fail("not a brickyard recording (no topics table)");
  auto text = [&](int col) {
    const unsigned char* t = sqlite3_column_text(st, col);
    return t ? std::string(reinterpret_cast<const char*>(t)) : std::string();
  };
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW)
    topics_.push_back({sqlite3_column_int64(st, 0), text(1), text(2), text(3), text(4)});
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) fail("reading its topics");
}

Recording::~Recording() {
  if (db_) sqlite3_close(db_);
}

void Recording::fail(const std::string& what) const {
  throw RecordingError(path_ + ": " + what + (db_ ? std::string(" (") + sqlite3_errmsg(db_) + ")" : ""));
}

const RecordedTopic* Recording::topic(const std::string& name) const {
  for (const auto& t : topics_)
    if (t.name == name) return &t;
  return nullptr;
}

std::string Recording::metadata(const std::string& key) const {
  if (mcap_) {
    const auto m = mcap_->metadata().find("brickyard");
    if (m == mcap_->metadata().end()) return {};
    const auto v = m->second.find(key);
    return v == m->second.end() ? std::string() : v->second;
  }
  sqlite3_stmt* st = nullptr;
  std::string v;
  if (sqlite3_prepare_v2(db_, "SELECT value FROM metadata WHERE key = ?", -1, &st, nullptr) == SQLITE_OK) {
    sqlite3_bind_text(st, 1, key.c_str(), -1, SQLITE_TRANSIENT);
    if (sqlite3_step(st) == SQLITE_ROW && sqlite3_column_text(st, 0))
      v = reinterpret_cast<const char*>(sqlite3_column_text(st, 0));
  }
  sqlite3_finalize(st);
  return v;
}

std::vector<RecordedSample> Recording::samples(const RecordedTopic& t) const {
  if (mcap_) {
    std::vector<RecordedSample> out;
    const std::set<std::uint16_t> only{static_cast<std::uint16_t>(t.id)};
    mcap_->read(
        [&](const mcap::MessageView& m) {
          RecordedSample s;
          s.stamp_ns = static_cast<std::int64_t>(m.log_time);
          s.data.assign(m.data, m.data + m.size);
          out.push_back(std::move(s));
        },
        &only);
    return out;
  }
  sqlite3_stmt* st = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT timestamp, data FROM messages WHERE topic_id = ? ORDER BY id", -1, &st, nullptr) != SQLITE_OK)
    fail("not a brickyard recording (no messages table)");
  sqlite3_bind_int64(st, 1, t.id);
  std::vector<RecordedSample> out;
  int rc;
  while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
    if (sqlite3_column_type(st, 1) != SQLITE_BLOB || sqlite3_column_type(st, 0) != SQLITE_INTEGER) {
      sqlite3_finalize(st);
      fail("sample " + std::to_string(out.size()) + " of " + t.name + " is not a timestamp and a blob");
    }
    RecordedSample s;
    s.stamp_ns = sqlite3_column_int64(st, 0);
    const auto* b = static_cast<const unsigned char*>(sqlite3_column_blob(st, 1));
    s.data.assign(b, b + sqlite3_column_bytes(st, 1));
    out.push_back(std::move(s));
  }
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) fail("reading the samples of " + t.name);
  return out;
}

}  // namespace brickyard::replay
