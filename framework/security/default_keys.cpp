#include "security/default_keys.hpp"

#include "math/fnv1a.hpp"

#include "security/documents.hpp"
#include "security/security_files.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>

namespace brickyard::fw::security {

namespace fs = std::filesystem;

namespace {

// $XDG_STATE_HOME/brickyard/keys, or $HOME/.local/state/brickyard/keys.
fs::path state_keys_root(const GraphDecl& g) {
  const char* xdg = std::getenv("XDG_STATE_HOME");
  const char* home = std::getenv("HOME");
  if (xdg && *xdg == '/') return fs::path(xdg) / "brickyard" / "keys";
  if (home && *home == '/') return fs::path(home) / ".local" / "state" / "brickyard" / "keys";
  throw InvalidInput(g.where("/transport/security"),
                     "a split run is secured by default with keys kept under $XDG_STATE_HOME or $HOME, and neither is set: name a "
                     "folder (`brickyard security init`) or set HOME");
}

// Made as needed; brickyard/ and keys/ 0700: what is under them are secrets.
void make_private_dirs(const fs::path& root, const GraphDecl& g) {
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec || !fs::is_directory(root))
    throw InvalidInput(g.where("/transport/security"), "cannot make " + root.string() + " for the run's default keys: " + ec.message());
  for (const fs::path& p : {root, root.parent_path()}) fs::permissions(p, fs::perms::owner_all, fs::perm_options::replace, ec);
}

std::string folder_name(const GraphDecl& g) {
  std::string name = g.name.empty() ? fs::path(g.file).stem().string() : g.name;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  return name.substr(0, 64);
}

bool keys_valid(const std::string& dir, const std::set<std::string>& processes) {
  std::set<std::string> ids = processes;
  ids.insert(kObserver);
  for (const auto& id : ids) {
    const DdsSecurity f = files_of(dir, id);
    if (!unreadable(f).empty() || !problems(f).empty()) return false;
  }
  return true;
}

// Held while the keys are checked and made; released when it goes (the descriptor closed).
class FolderLock {
 public:
  FolderLock(const std::string& file, const GraphDecl& g) : fd_(::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600)) {
    if (fd_ < 0 || ::flock(fd_, LOCK_EX) != 0)
      throw InvalidInput(g.where("/transport/security"), "cannot lock " + file + " to make the run's default keys");
  }
  ~FolderLock() { ::close(fd_); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_;
};

}  // namespace

SecurityChoice security_choice(const GraphDecl& g) {
  if (g.transport.security.empty()) return SecurityChoice::by_default;
  return g.transport.security == kSecurityOff ? SecurityChoice::off : SecurityChoice::folder;
}

std::string default_keys_dir(const ResolvedGraph& all) {
  const GraphDecl& g = *all.decl;
  std::string what = fs::absolute(g.file).lexically_normal().string();
  for (const auto& [id, access] : access_of(all)) {
    what += "\n" + id + " publish";
    for (const auto& t : access.publish) what += " " + t;
    what += " subscribe";
    for (const auto& t : access.subscribe) what += " " + t;
  }
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(math::fnv1a(what)));
  return (state_keys_root(g) / (folder_name(g) + "-" + hash)).string();
}

DefaultKeys ensure_default_keys(const ResolvedGraph& all) {
  DefaultKeys k;
  k.dir = default_keys_dir(all);
  make_private_dirs(fs::path(k.dir).parent_path(), *all.decl);
  FolderLock lock(k.dir + ".lock", *all.decl);
  if (keys_valid(k.dir, all.processes)) return k;
  InitOptions o;
  o.protection = Protection::encrypt;
  init(all, k.dir, o);
  k.made = true;
  return k;
}

}  // namespace brickyard::fw::security
