#pragma once
// A split run is secured unless its graph says otherwise (issue 44, docs/security.md "By
// default"): a graph whose wires cross processes and whose `transport.security` names no folder
// runs with keys made for it on its first split run and kept for the next ones, every message
// encrypted. `"security": "off"` is the explicit, warned way out.
//
// Where: STATE/brickyard/keys/NAME-HASH, STATE being $XDG_STATE_HOME or else $HOME/.local/state
// (the folders 0700). HASH covers the graph file's absolute path and what each process may
// publish and subscribe (documents.hpp's access_of), so every process of one run finds the same
// folder, and a graph whose wires changed gets keys of its own rather than permissions that no
// longer fit. The first process to need the keys makes them under a lock (flock on
// NAME-HASH.lock): the others of its run wait for it and read them.
#include "graph/resolve.hpp"

#include <string>

namespace brickyard::fw::security {

// What a graph's `transport.security` asks of a run that crosses processes.
enum class SecurityChoice { by_default, off, folder };
SecurityChoice security_choice(const GraphDecl& g);

// The keys folder of a split run of `all` (resolved with every node) whose graph names none.
std::string default_keys_dir(const ResolvedGraph& all);

struct DefaultKeys {
  std::string dir;
  bool made = false;  // made (or remade: a certificate expired, a file gone) by this call
};

// The folder, its keys made first when missing or no longer valid. Throws InvalidInput when the
// state folder cannot be found or made (naming HOME and the graph's /transport/security), and
// io::WriteError when a file cannot be written.
DefaultKeys ensure_default_keys(const ResolvedGraph& all);

}  // namespace brickyard::fw::security
