#pragma once
#include "cli/arguments.hpp"
#include "graph/graph.hpp"

namespace brickyard::fw::cli {

// Runs graph g with the command line's options (or, validate_only, checks everything and starts
// nothing): the run's exit code (0 success, 1 failed, 2 invalid input). A graph whose nodes name
// several processes is supervised (cli/supervisor.hpp) unless --process or --one-process says
// otherwise. `brickyard map build` runs its built-in graph through it too.
int run_graph(const Args& a, GraphDecl g, bool validate_only);

}  // namespace brickyard::fw::cli
