#pragma once
// `brickyard topic list | echo TOPIC | hz TOPIC`: a running graph's wires, seen over DDS from
// outside it (real clock, docs/live.md). Topics are NODE.PORT; samples print as JSON lines,
// decoded by their type's IDL.
#include <optional>
#include <string>

namespace brickyard::fw {

struct TopicOptions {
  std::string verb;                 // list, echo, hz
  std::string topic;                // NODE.PORT (echo, hz)
  int domain = 0;
  std::string security, identity;  // --security DIR (--identity NAME): join a secured graph as that identity
  bool ros2_naming = false;        // --naming ros2: the graph's topics carry ROS 2's names
  std::optional<double> duration;  // seconds to listen (list: 2 by default; echo, hz: until --count or Ctrl-C)
  std::optional<long> count;       // echo, hz: stop after this many samples
  double wait = 5;                  // echo, hz: seconds to wait for the topic's writer
};

// Exit code: 0 heard what was asked; 1 nothing heard (no writer, no sample), with the reason on
// stderr; 2 bad input (an unknown verb, a topic that is not NODE.PORT, a type this build does
// not know).
int topic_command(const TopicOptions& o);

}  // namespace brickyard::fw
