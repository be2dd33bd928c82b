#include "security/security_files.hpp"

#include "graph/diagnostics.hpp"
#include "io/whole_file.hpp"
#include "security/pki.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace brickyard::fw::security {

namespace fs = std::filesystem;

namespace {

const char* kOrganisation = "Brickyard";
// X.509 bounds a common name at 64 characters (RFC 5280's ub-common-name).
constexpr std::size_t kMaxCommonName = 64;

[[noreturn]] void refuse(const std::string& culprit, const std::string& why) { throw InvalidInput(culprit, why); }

std::string subject_for(const std::string& identity) { return std::string("CN=") + identity + ",O=" + kOrganisation; }

// Whole or not at all (a reader never sees half a key or document); a key 0600 before a byte of it
// is written. A write that fails is io::WriteError (exit 1), not bad input.
void write_file(const fs::path& path, const std::string& text, bool secret) {
  io::write_whole_file(path.string(), text, secret ? 0600 : 0644);
}

// The keys folder's files, written into a staging folder beside it and moved in only once every
// one is written: a write that fails (a full disk) leaves the folder as it was, not half made.
// Renames within one file system need no space. The staging folder goes whatever happens.
class Staging {
 public:
  explicit Staging(const fs::path& dir) : dir_(dir), at_(dir.parent_path() / ("." + dir.filename().string() + ".init")) {
    std::error_code ec;
    fs::remove_all(at_, ec);
    fs::create_directories(at_, ec);
    if (ec) refuse(dir.string(), "cannot write beside it (" + at_.string() + ": " + ec.message() + ")");
  }
  ~Staging() {
    std::error_code ec;
    fs::remove_all(at_, ec);
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;

  void put(const fs::path& rel, const std::string& text, bool secret) {
    std::error_code ec;
    fs::create_directories((at_ / rel).parent_path(), ec);
    if (ec) throw io::WriteError((at_ / rel).parent_path().string() + ": cannot be made (" + ec.message() + ")");
    write_file(at_ / rel, text, secret);
    files_.push_back(rel);
  }

  void commit() {
    for (const auto& rel : files_) {
      std::error_code ec;
      fs::create_directories((dir_ / rel).parent_path(), ec);
      if (!ec) fs::rename(at_ / rel, dir_ / rel, ec);
      if (ec) throw io::WriteError((dir_ / rel).string() + ": cannot be written (" + ec.message() + ")");
    }
  }

 private:
  fs::path dir_, at_;
  std::vector<fs::path> files_;
};

std::string read_text(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// "YYYY-MM-DDThh:mm:ss", UTC, `offset_s` from now: the permissions' validity.
std::string utc(std::time_t offset_s) {
  const std::time_t t = std::time(nullptr) + offset_s;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S", &tm);
  return buf;
}

}  // namespace

DdsSecurity files_of(const std::string& dir, const std::string& identity) {
  const fs::path d = fs::absolute(dir).lexically_normal();
  DdsSecurity f;
  f.identity_ca = (d / "identity_ca.pem").string();
  f.permissions_ca = (d / "permissions_ca.pem").string();
  f.governance = (d / "governance.p7s").string();
  f.cert = (d / identity / "cert.pem").string();
  f.key = (d / identity / "key.pem").string();
  f.permissions = (d / identity / "permissions.p7s").string();
  return f;
}

std::vector<std::string> unreadable(const DdsSecurity& f) {
  std::vector<std::string> out;
  for (const std::string* p : {&f.identity_ca, &f.permissions_ca, &f.governance, &f.cert, &f.key, &f.permissions}) {
    std::error_code ec;
    if (!fs::is_regular_file(*p, ec)) out.push_back(*p + ": " + (fs::exists(*p, ec) ? "not a file" : "does not exist"));
    else if (::access(p->c_str(), R_OK) != 0) out.push_back(*p + ": cannot be read (" + std::strerror(errno) + ")");
  }
  return out;
}

DdsSecurity check_run(const GraphDecl& g, const std::string& process, const std::set<std::string>& processes) {
  Diagnostics d;
  const std::string where = g.where("/transport/security");
  std::error_code ec;
  if (!fs::is_directory(g.transport.security, ec)) {
    d.add(where, g.transport.security + " is not a folder: make it with `brickyard security init " + g.file + " --out " + g.transport.security + "`");
    d.raise_if_any();
  }
  for (const std::string& p : process.empty() ? processes : std::set<std::string>{process}) {
    const DdsSecurity f = files_of(g.transport.security, p);
    const auto missing = unreadable(f);
    for (const auto& why : missing)
      d.add(where, "process '" + p + "': " + why + " (`brickyard security init " + g.file + " --out " + g.transport.security +
                       "` makes every process's identity)");
    if (missing.empty())
      for (const auto& why : problems(f)) d.add(where, "process '" + p + "': " + why);
  }
  d.raise_if_any();
  return process.empty() ? DdsSecurity{} : files_of(g.transport.security, process);
}

std::vector<std::string> problems(const DdsSecurity& f) {
  std::vector<std::string> out;
  if (const std::string why = pki::identity_problem(read_text(f.identity_ca), read_text(f.cert), read_text(f.key)); !why.empty())
    out.push_back(f.cert + ": " + why);
  const std::string perm_ca = read_text(f.permissions_ca);
  for (const std::string* doc : {&f.governance, &f.permissions})
    if (!pki::smime_verify(perm_ca, read_text(*doc))) out.push_back(*doc + ": its signature does not verify against " + f.permissions_ca);
  return out;
}

DdsSecurity security_identity(const std::string& dir, const std::string& identity) {
  const DdsSecurity f = files_of(dir, identity);
  Diagnostics d;
  for (const auto& why : unreadable(f)) d.add("--security " + dir, "identity '" + identity + "': " + why);
  d.raise_if_any();
  for (const auto& why : problems(f)) d.add("--security " + dir, "identity '" + identity + "': " + why);
  d.raise_if_any();
  return f;
}

InitResult init(const ResolvedGraph& g, const std::string& dir, const InitOptions& o) {
  const auto access = access_of(g);
  for (const auto& [identity, a] : access) {
    (void)a;
    if (identity.size() > kMaxCommonName)
      refuse(g.decl->file, "process '" + identity.substr(0, 40) + "…' has a name of " + std::to_string(identity.size()) +
                               " characters; a certificate's common name holds at most 64");
  }
  if (g.nodes.empty()) refuse(g.decl->file, "the graph has no nodes: no process to make an identity for");
  for (const auto& n : g.nodes)
    if ((n.decl->process.empty() ? kDefaultProcess : n.decl->process) == kObserver)
      refuse(g.decl->file, "node '" + n.decl->name + "' runs in process 'observer', the name of the identity that reads every topic: rename the process");
  fs::path d = fs::path(dir).lexically_normal();
  if (!d.has_filename()) d = d.parent_path();
  std::error_code ec;
  if (fs::exists(d, ec) && !fs::is_directory(d, ec)) refuse(dir, "cannot create the folder: it exists and is not a folder");
  Staging staged(d);
  InitResult r;
  pki::Identity ca;
  const fs::path ca_cert = d / "identity_ca.pem", ca_key = d / "ca_key.pem";
  if (fs::exists(ca_cert, ec) && fs::exists(ca_key, ec)) {
    ca = {read_text(ca_key), read_text(ca_cert)};
    try {
      (void)pki::subject_of(ca.cert_pem);
      (void)pki::smime_sign(ca, "check");  // the key and certificate work together
    } catch (const std::exception& e) {
      refuse(ca_cert.string(), std::string("holds no usable CA (") + e.what() + "): remove it and ca_key.pem to make a new one");
    }
    r.reused_ca = true;
  } else {
    ca = pki::make_ca(std::string("CN=Brickyard graph CA ") + (g.decl->name.empty() ? fs::path(g.decl->file).stem().string() : g.decl->name) +
                          ",O=" + kOrganisation,
                      o.days);
    staged.put("ca_key.pem", ca.key_pem, true);
    staged.put("identity_ca.pem", ca.cert_pem, false);
  }
  staged.put("permissions_ca.pem", ca.cert_pem, false);
  const std::string gov = governance_xml(o.protection);
  staged.put("governance.xml", gov, false);
  staged.put("governance.p7s", pki::smime_sign(ca, gov), false);
  const std::string not_before = utc(-3600), not_after = utc(static_cast<std::time_t>(o.days) * 86400);
  for (const auto& [identity, a] : access) {
    const pki::Identity id = pki::make_identity(ca, subject_for(identity), o.days);
    staged.put(fs::path(identity) / "key.pem", id.key_pem, true);
    staged.put(fs::path(identity) / "cert.pem", id.cert_pem, false);
    const std::string perm = permissions_xml(identity, pki::subject_of(id.cert_pem), a, not_before, not_after);
    staged.put(fs::path(identity) / "permissions.xml", perm, false);
    staged.put(fs::path(identity) / "permissions.p7s", pki::smime_sign(ca, perm), false);
    r.identities.push_back(identity);
  }
  staged.commit();
  return r;
}

}  // namespace brickyard::fw::security
