// `brickyard topic list | echo NODE.PORT | hz NODE.PORT`: the command line as TopicOptions, for
// cli/topic_command.hpp.
#include "cli/command_table.hpp"
#include "cli/topic_command.hpp"

namespace brickyard::fw::cli {

int cmd_topic(const Args& a) {
  if (a.more.size() > 1) usage_error(a.more[1], "unexpected argument");
  TopicOptions o;
  o.verb = a.target;
  o.topic = a.more.empty() ? "" : a.more[0];
  o.domain = a.domain.value_or(0);
  o.duration = a.duration;
  o.count = a.count;
  o.security = a.security;
  o.identity = a.identity;
  o.ros2_naming = a.ros2_naming;
  return topic_command(o);
}

}  // namespace brickyard::fw::cli
