#include "cli/report.hpp"

#include "cli/command_table.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <vector>

extern char** environ;

namespace brickyard::fw::cli {

namespace fs = std::filesystem;

// Started with an argument vector, no shell: a folder's name is never parsed.
int run_report(const std::string& dir, bool quiet) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const std::string tool = (self.parent_path() / "brickyard-report").string();
  if (ec || !fs::exists(tool)) {
    std::fprintf(stderr, "[brickyard] brickyard-report not found beside %s\n", self.string().c_str());
    return 2;
  }
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (quiet) posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  std::vector<char*> argv = {const_cast<char*>(tool.c_str()), const_cast<char*>(dir.c_str()), nullptr};
  pid_t pid = 0;
  const int err = posix_spawn(&pid, tool.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (err != 0) return 2;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

int cmd_report(const Args& a) {
  if (a.target.empty()) usage_error("report", "needs a run folder (brickyard run --out DIR)");
  return run_report(a.target, false);
}

}  // namespace brickyard::fw::cli
