#pragma once
// `brickyard run GRAPH` of a graph whose nodes run in several processes (real clock): the
// supervisor (docs/reliability.md). It starts each process as a child —
// `brickyard run GRAPH --process P` — relays what it says line by line under its name, and
// watches it. A child that dies is named with its nodes, its signal or exit code and its own
// last word (the node that crashed, from its summary); its shared memory is removed, its summary
// written when it could not write one (SIGKILL), and its restart policy applied (the graph's
// "processes"). The run fails when a process that may not die dies, or any process fails. One
// process finishing the run (its referee, a sink) ends the others with SIGINT.
#include "graph/graph.hpp"

#include <optional>
#include <string>
#include <vector>

namespace brickyard::fw {

// Every process the supervisor starts gets a participant id of its own, the restarted ones too,
// below kSupervisedParticipants; their ports, 7400 + 250 domain + 11 + 2 id, fit under 65536 on
// domains up to kLastSupervisedDomain (Fast DDS refuses the run's participants past it).
constexpr int kSupervisedParticipants = 120;
constexpr int kLastSupervisedDomain = 231;

struct SuperviseOptions {
  std::string graph_file;               // as given on the command line
  std::vector<std::string> child_flags;  // passed to every child as they are (--set, --arg, --seed, ...)
  std::optional<double> duration_s;     // the run's; a restarted child gets what is left of it
  int domain = 0;
  std::string out;                      // --out DIR: DIR/summary.json, DIR/PROCESS[.restartK]/...
  bool quiet = false;
};

// The run's exit code: 0 success or interrupted (as one process), 1 failed, 2 invalid input (a child said so).
int supervise(const GraphDecl& g, const SuperviseOptions& o);

}  // namespace brickyard::fw
