#pragma once
// A graph's DDS security folder, as `brickyard security init GRAPH --out DIR` makes it and a
// run with `transport.security: DIR` reads it (docs/security.md):
//
//   DIR/identity_ca.pem        the CA that vouches for every participant (certificate only)
//   DIR/permissions_ca.pem     the CA that signed the governance and permissions (the same CA)
//   DIR/ca_key.pem             the CA's private key (0600): keep it off the car
//   DIR/governance.p7s         signed domain rules (governance.xml beside it, for reading)
//   DIR/IDENTITY/cert.pem      one identity per process, and `observer`
//   DIR/IDENTITY/key.pem       its private key (0600)
//   DIR/IDENTITY/permissions.p7s  what it may publish and subscribe (permissions.xml beside it)
#include "graph/resolve.hpp"
#include "security/documents.hpp"
#include "transport/dds.hpp"

#include <set>
#include <string>
#include <vector>

namespace brickyard::fw::security {

// The files one participant gives Fast DDS (absolute paths).
DdsSecurity files_of(const std::string& dir, const std::string& identity);

// The files of `identity` under `dir` that cannot be read, each "PATH: why"; empty when all can.
std::vector<std::string> unreadable(const DdsSecurity& files);

// Why the readable files would not let the participant in: its certificate not the CA's, out
// of its validity, or not its key's; the governance or permissions not signed by the permissions
// CA. Each "PATH: why"; empty when none.
std::vector<std::string> problems(const DdsSecurity& files);

// The identity files of a run of `g` checked readable: for `process`, or for each of `processes`
// when it is empty (a supervised run, `validate`). InvalidInput naming /transport/security and each
// file that is not, with how to make them. Returns `process`'s files (empty when none given).
DdsSecurity check_run(const GraphDecl& g, const std::string& process, const std::set<std::string>& processes);

// `identity`'s files under `dir` for a tool joining a secured graph (`brickyard topic`, `bag
// play`): InvalidInput naming --security and each file that cannot be read.
DdsSecurity security_identity(const std::string& dir, const std::string& identity);

struct InitOptions {
  Protection protection = Protection::encrypt;
  int days = 365;  // the certificates' and permissions' validity
};

struct InitResult {
  std::vector<std::string> identities;  // made, in order
  bool reused_ca = false;               // the folder's CA kept (its identities and documents made anew)
};

// Make (or remake, keeping an existing CA) the folder for `g` (resolved with every node). Every
// file is written whole under a temporary name and renamed; keys are 0600. Throws InvalidInput
// naming the culprit (a process name a certificate cannot carry, a folder that cannot be made),
// io::WriteError naming a file that cannot be written (a full disk).
InitResult init(const ResolvedGraph& g, const std::string& dir, const InitOptions& o);

}  // namespace brickyard::fw::security
