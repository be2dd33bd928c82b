#pragma once
// What each process of a graph may do on DDS, derived from its wires, and the OMG DDS Security
// 1.1 documents that say it: the domain governance (every participant authenticated, every
// topic's readers and writers access-controlled, traffic signed or encrypted) and one
// permissions document per identity (the topics it may publish and subscribe, nothing else).
// Framework-free text; pki.hpp signs it; the layout on disk is security_files.hpp's.
#include "graph/resolve.hpp"

#include <map>
#include <set>
#include <string>

namespace brickyard::fw::security {

// What the documents ask of the traffic.
enum class Protection {
  sign,     // every RTPS message signed (AES-GMAC): nobody without an identity forges or reads by DDS; a sniffer of the path could read
  encrypt,  // every message, discovery and every topic's data encrypted (AES-GCM)
};

struct Access {
  std::set<std::string> publish, subscribe;  // DDS topic names (topic_name())
};

// The identity that reads every topic and writes none: `brickyard topic` against a secured graph.
inline const std::string kObserver = "observer";

// Per process of the graph (kDefaultProcess for nodes that name none): publish every output of its
// nodes (each has a writer), subscribe the outputs wired to its nodes from another process; and
// kObserver: subscribe every output. `g` resolved with every node (resolve_graph without a process).
std::map<std::string, Access> access_of(const ResolvedGraph& g);

std::string governance_xml(Protection p);

// `subject`: the identity certificate's subject ("CN=a,O=Brickyard"); `not_before`/`not_after`:
// "YYYY-MM-DDThh:mm:ss" (UTC).
std::string permissions_xml(const std::string& identity, const std::string& subject, const Access& a,
                            const std::string& not_before, const std::string& not_after);

}  // namespace brickyard::fw::security
