// `brickyard new-plugin NAME --dir DIR [--role ROLE]`: a plugin project scaffolded from the SDK
// template, or from a role's: a plugin that already plays the role.
#include "cli/command_table.hpp"
#include "cli/commands.hpp"

#include <iostream>

namespace brickyard::fw::cli {

int cmd_new_plugin(const Args& a) {
  if (a.target.empty()) usage_error("new-plugin", "needs a NAME");
  if (a.dir.empty()) usage_error("new-plugin", "needs --dir DIR");
  const std::string template_dir = find_template_dir();
  scaffold_plugin(a.target, a.dir, a.role.empty() ? template_dir : find_role_template_dir(template_dir, a.role));
  std::cout << "wrote plugin project " << a.target << " in " << a.dir << "\n"
            << "build it:  cmake -S " << a.dir << " -B " << a.dir << "/build -DCMAKE_PREFIX_PATH=<brickyard prefix> && cmake --build "
            << a.dir << "/build\n";
  return 0;
}

}  // namespace brickyard::fw::cli
