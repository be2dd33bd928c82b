#pragma once
#include <string>

namespace brickyard::fw::cli {

// brickyard-report, installed beside this executable, on a run folder (writes DIR/report.html);
// its exit code, 2 when it is not there. quiet: its standard output goes to /dev/null.
int run_report(const std::string& dir, bool quiet);

}  // namespace brickyard::fw::cli
