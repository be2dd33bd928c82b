#include "record/recorder.hpp"

#include "cdr/idl_model.hpp"
#include "cdr/ros2_msgs.hpp"
#include "cdr/ros2_std_types.hpp"
#include "mcap/mcap_writer.hpp"
#include "mcap/ros2_profile.hpp"
#include "transport/wire_types.hpp"

#include <sqlite3.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <map>
#include <stdexcept>

#include <fcntl.h>
#include <stdio.h>  // renameat2
#include <sys/stat.h>
#include <unistd.h>

namespace brickyard::fw {

namespace {
struct IdlText {
  const char* type;
  const char* text;
};
const IdlText kIdl[] = {
#include "idl_texts.inc"
};
// Commit every this many samples, or once the batch is a second old (on the wall clock, or on
// the run's: a sim run goes many times faster than real time), whichever comes first: a crash
// loses at most the last second, and one transaction per sample would make recording the
// bottleneck. (With a batch of samples alone, a slow run killed at 4 s had committed none of
// its 150 samples.)
constexpr std::uint64_t kBatch = 2000;
constexpr std::int64_t kBatchNs = 1'000'000'000;
}  // namespace

const char* idl_text(const std::string& type) {
  for (const auto& t : kIdl)
    if (type == t.type) return t.text;
  return cdr::ros2_standard_idl(type);
}

std::string omgidl_schema(const std::string& idl) { return cdr::self_contained_idl(idl); }

// FILE.db3, or FILE.db3.part (a recording not closed: a killed run's).
bool is_sqlite_recording(const std::string& path) {
  std::filesystem::path p(path);
  if (p.extension() == ".part") p = p.stem();
  return p.extension() == ".db3";
}

bool topic_selected(const std::string& topic, const std::vector<std::string>& patterns) {
  // '*' matches any run of characters. Greedy with one backtrack point, the last star: at most
  // |pattern| x |topic| steps, never exponential (a recursive match took 73 s on 40 stars).
  auto match = [](const std::string& p, const std::string& s) {
    std::size_t i = 0, j = 0, star = std::string::npos, mark = 0;
    while (j < s.size()) {
      if (i < p.size() && p[i] == '*') star = i++, mark = j;
      else if (i < p.size() && p[i] == s[j]) ++i, ++j;
      else if (star != std::string::npos) i = star + 1, j = ++mark;
      else return false;
    }
    while (i < p.size() && p[i] == '*') ++i;
    return i == p.size();
  };
  for (const auto& p : patterns)
    if (match(p, topic)) return true;
  return false;
}

struct Recorder::Topic {
  std::string name, type;
  std::uint16_t channel = 0, schema = 0;  // MCAP
};

Recorder::Recorder(const std::string& path, const std::string& compression, const std::string& profile)
    : path_(path), part_(path + ".part"), ros2_(profile == "ros2") {
  if (profile != "brickyard" && profile != "ros2") throw std::runtime_error(path + ": profile '" + profile + "' is neither brickyard nor ros2");
  if (ros2_ && is_sqlite_recording(path)) throw std::runtime_error(path + ": the ros2 profile is MCAP's: name a .mcap file");
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) throw std::runtime_error(path + ": exists; a recording is never overwritten");
  // Written as PATH.part, created exclusively (two runs given the same FILE cannot both pass an
  // exists() check), and renamed PATH when closed: a file at PATH is a whole recording.
  const int fd = ::open(part_.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0) {
    if (errno == EEXIST)
      throw std::runtime_error(part_ + ": exists: a run recording into " + path + " is under way, or was killed (what it "
                               "recorded is in that file: brickyard bag info " + part_ + "); move it away");
    throw std::runtime_error(path + ": cannot create " + part_ + " (" + std::strerror(errno) + ")");
  }
  ::close(fd);
  if (!is_sqlite_recording(path)) {
    mcap::WriterOptions o;
    if (!mcap::parse_compression(compression, o.compression)) {
      ::unlink(part_.c_str());
      throw std::runtime_error(path + ": compression '" + compression + "' is none of zstd, lz4, none");
    }
    if (ros2_) o.profile = "ros2";
    ::unlink(part_.c_str());  // the MCAP writer makes it, exclusively, itself
    mcap_ = std::make_unique<mcap::Writer>(part_, o);
    return;
  }
  if (sqlite3_open_v2(part_.c_str(), &db_, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
    sqlite3_close(db_);
    db_ = nullptr;
    ::unlink(part_.c_str());
    throw std::runtime_error(path + ": cannot open as a database");
  }
  try {
    create_schema();
  } catch (...) {
    sqlite3_finalize(insert_);
    sqlite3_close(db_);
    db_ = nullptr;
    for (const char* end : {"", "-wal", "-shm"}) ::unlink((part_ + end).c_str());
    throw;
  }
}

void Recorder::create_schema() {
  // The file is written by this process alone and only whole at close(): no journal needed
  // beyond what keeps it consistent after a crash (WAL, synchronous NORMAL).
  exec("PRAGMA journal_mode=WAL");
  exec("PRAGMA synchronous=NORMAL");
  exec("CREATE TABLE metadata(key TEXT PRIMARY KEY, value TEXT NOT NULL)");
  exec("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL UNIQUE, type TEXT NOT NULL, "
       "type_hash TEXT NOT NULL, serialization_format TEXT NOT NULL, idl TEXT NOT NULL)");
  exec("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL REFERENCES topics(id), "
       "timestamp INTEGER NOT NULL, data BLOB NOT NULL)");
  exec("CREATE INDEX messages_topic_timestamp ON messages(topic_id, timestamp)");
  if (sqlite3_prepare_v2(db_, "INSERT INTO messages(topic_id, timestamp, data) VALUES(?, ?, ?)", -1, &insert_, nullptr) != SQLITE_OK)
    fail("prepare");
}

Recorder::~Recorder() {
  try {
    close();
  } catch (...) {
  }
}

void Recorder::fail(const std::string& what) {
  throw std::runtime_error(path_ + ": recording: " + what + (db_ ? std::string(" (") + sqlite3_errmsg(db_) + ")" : ""));
}

void Recorder::exec(const char* sql) {
  char* err = nullptr;
  if (sqlite3_exec(db_, sql, nullptr, nullptr, &err) != SQLITE_OK) {
    const std::string e = err ? err : "?";
    sqlite3_free(err);
    fail(std::string(sql) + ": " + e);
  }
}

void Recorder::set_metadata(const std::string& key, const std::string& value) {
  std::lock_guard<std::mutex> l(m_);
  if (mcap_) {
    metadata_.emplace_back(key, value);
    return;
  }
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db_, "INSERT OR REPLACE INTO metadata(key, value) VALUES(?, ?)", -1, &st, nullptr);
  sqlite3_bind_text(st, 1, key.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 2, value.c_str(), -1, SQLITE_TRANSIENT);
  const int rc = sqlite3_step(st);
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) fail("metadata");
}

int Recorder::add_topic(const std::string& name, const std::string& type) {
  std::lock_guard<std::mutex> l(m_);
  const auto* entry = find_wire_type(type);
  const char* idl = idl_text(type);
  if (!entry || !idl) fail("no type support for " + type);
  auto t = std::make_unique<Topic>();
  t->name = name;
  t->type = type;
  if (mcap_) {
    write_metadata_once();
    std::uint16_t schema = 0;
    for (const auto& other : topics_)
      if (other->type == type) schema = other->schema;
    if (schema == 0 && ros2_)
      schema = mcap_->add_schema(mcap::ros2_schema_name(type), "ros2msg",
                                 cdr::ros2msg_schema(cdr::parse_idl(omgidl_schema(idl)), type, mcap::kRos2Package));
    if (schema == 0) schema = mcap_->add_schema(type, "omgidl", omgidl_schema(idl));
    t->schema = schema;
    t->channel = mcap_->add_channel(schema, ros2_ ? mcap::ros2_topic_name(name) : name, "cdr", {{"type_hash", entry->hash}});
    topics_.push_back(std::move(t));
    return static_cast<int>(topics_.size());
  }
  sqlite3_stmt* st = nullptr;
  sqlite3_prepare_v2(db_, "INSERT INTO topics(id, name, type, type_hash, serialization_format, idl) VALUES(?, ?, ?, ?, 'cdr', ?)", -1,
                     &st, nullptr);
  const int id = static_cast<int>(topics_.size()) + 1;
  sqlite3_bind_int(st, 1, id);
  sqlite3_bind_text(st, 2, name.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 3, type.c_str(), -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 4, entry->hash, -1, SQLITE_TRANSIENT);
  sqlite3_bind_text(st, 5, idl, -1, SQLITE_TRANSIENT);
  const int rc = sqlite3_step(st);
  sqlite3_finalize(st);
  if (rc != SQLITE_DONE) fail("topic " + name);
  topics_.push_back(std::move(t));
  return id;
}

void Recorder::write_metadata_once() {
  if (metadata_.empty()) return;  // the run's, once: set before any channel
  mcap_->add_metadata("brickyard", {metadata_.begin(), metadata_.end()});
  metadata_.clear();
}

int Recorder::add_channel(const std::string& topic, const std::string& encoding, const std::string& schema_name,
                          const std::string& schema_encoding, const std::string& schema) {
  std::lock_guard<std::mutex> l(m_);
  if (!mcap_) return 0;
  write_metadata_once();
  auto t = std::make_unique<Topic>();
  t->name = topic;
  t->type = schema_name;
  for (const auto& other : topics_)
    if (other->type == schema_name) t->schema = other->schema;
  if (t->schema == 0) t->schema = mcap_->add_schema(schema_name, schema_encoding, schema);
  t->channel = mcap_->add_channel(t->schema, topic, encoding);
  topics_.push_back(std::move(t));
  return static_cast<int>(topics_.size());
}

void Recorder::write(int topic, std::int64_t stamp_ns, const unsigned char* cdr, std::size_t size) {
  std::lock_guard<std::mutex> l(m_);
  if (topic < 1 || topic > static_cast<int>(topics_.size())) return;
  if (!db_ && !mcap_) return;
  if (failed_) return;  // after a failed write: the run is stopping, nothing more is written
  Topic& t = *topics_[topic - 1];
  if (mcap_) {
    if (in_transaction_ == 0) batch_wall_ = std::chrono::steady_clock::now(), batch_stamp_ = stamp_ns;
    const auto when = static_cast<std::uint64_t>(std::max<std::int64_t>(stamp_ns, 0));
    try {
      mcap_->write(t.channel, when, when, cdr, size);
    } catch (const std::exception& e) {  // (a full disk) what was written stays, up to the last whole chunk
      failed_ = true;
      throw std::runtime_error(std::string(e.what()) + " (a sample of " + t.name + ")");
    }
    ++messages_;
    bytes_ += size;
    ++in_transaction_;
    flush_batch(stamp_ns);
    return;
  }
  if (in_transaction_ == 0) {
    exec("BEGIN");
    batch_wall_ = std::chrono::steady_clock::now();
    batch_stamp_ = stamp_ns;
  }
  sqlite3_reset(insert_);
  sqlite3_bind_int(insert_, 1, topic);
  sqlite3_bind_int64(insert_, 2, stamp_ns);
  sqlite3_bind_blob(insert_, 3, cdr, static_cast<int>(size), SQLITE_STATIC);
  if (sqlite3_step(insert_) != SQLITE_DONE) {
    // (A full disk, the file gone.) What was committed stays; this batch is rolled back.
    const std::string why = sqlite3_errmsg(db_);
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    in_transaction_ = 0;
    failed_ = true;
    throw std::runtime_error(path_ + ": recording: writing a sample of " + t.name + " (" + why + ")");
  }
  ++messages_;
  bytes_ += size;
  ++in_transaction_;
  flush_batch(stamp_ns);
}

void Recorder::flush_batch(std::int64_t stamp_ns) {
  // MCAP: a chunk is written once it is a second old on either clock, or once it holds
  // chunk_size bytes (the writer). (Chunks of a second of the wall clock alone compress better,
  // 26.0 MB against 31 for the main job, but a sim run that crashes within its first wall second
  // kept nothing: evidence.faults.)
  const bool young = std::chrono::steady_clock::now() - batch_wall_ < std::chrono::nanoseconds(kBatchNs);
  if ((mcap_ || in_transaction_ < kBatch) && stamp_ns - batch_stamp_ < kBatchNs && young) return;
  in_transaction_ = 0;
  if (!mcap_) {
    try {
      exec("COMMIT");
    } catch (...) {  // what was committed before stays; this batch is rolled back, and no more written
      sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
      failed_ = true;
      throw;
    }
    return;
  }
  try {
    mcap_->flush();
  } catch (...) {
    failed_ = true;
    throw;
  }
}

// The closed recording takes its name; never over a file that appeared there meanwhile.
void Recorder::publish() {
  if (published_) return;
  published_ = true;
  if (failed_) return;  // a write failed: not whole, left as PATH.part (the run failed naming it)
  if (::renameat2(AT_FDCWD, part_.c_str(), AT_FDCWD, path_.c_str(), RENAME_NOREPLACE) != 0)
    throw std::runtime_error(path_ + ": the recording cannot take its name (" + std::strerror(errno) + "); it is kept as " + part_);
}

void Recorder::close() {
  std::lock_guard<std::mutex> l(m_);
  if (mcap_) {
    if (!metadata_.empty()) mcap_->add_metadata("brickyard", {metadata_.begin(), metadata_.end()}), metadata_.clear();
    auto w = std::move(mcap_);
    try {
      w->close();
    } catch (const std::exception& e) {
      published_ = true;  // not whole: left as PATH.part
      throw std::runtime_error(std::string(e.what()) + "; what was recorded is kept as " + part_);
    }
    publish();
    return;
  }
  if (!db_) return;
  // Finalized and closed whatever happens; the first error is reported after.
  std::string error;
  auto run = [&](const char* sql) {
    char* err = nullptr;
    if (sqlite3_exec(db_, sql, nullptr, nullptr, &err) != SQLITE_OK && error.empty()) error = std::string(sql) + ": " + (err ? err : "?");
    sqlite3_free(err);
  };
  if (in_transaction_ > 0) run("COMMIT");
  in_transaction_ = 0;
  sqlite3_finalize(insert_);
  insert_ = nullptr;
  run("PRAGMA wal_checkpoint(TRUNCATE)");
  run("PRAGMA journal_mode=DELETE");  // one self-contained file
  sqlite3_close_v2(db_);
  db_ = nullptr;
  if (!error.empty()) {
    published_ = true;  // not whole: left as PATH.part
    throw std::runtime_error(path_ + ": recording: " + error + "; what was recorded is kept as " + part_);
  }
  publish();
}

}  // namespace brickyard::fw
