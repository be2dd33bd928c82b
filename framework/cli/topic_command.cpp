#include "cli/topic_command.hpp"

#include "exec/executive.hpp"  // g_interrupt
#include "cdr/cdr_json.hpp"
#include "cdr/ros2_std_types.hpp"
#include "record/recorder.hpp"
#include "record/sample_serializer.hpp"
#include "security/security_files.hpp"
#include "transport/dds.hpp"
#include "transport/wire_types.hpp"

#include <brickyard/msgs/registry.hpp>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

namespace brickyard::fw {

namespace {

using Clock = std::chrono::steady_clock;

// "brickyard/node/port" (or ROS 2's "rt/brickyard/node/port") → "node.port"; other DDS topics as
// they are.
std::string ours(const std::string& dds) {
  const std::size_t from = dds.rfind("brickyard/", 0) == 0 ? 10 : dds.rfind("rt/brickyard/", 0) == 0 ? 13 : std::string::npos;
  if (from == std::string::npos) return dds;
  std::string t = dds.substr(from);
  const auto slash = t.find('/');
  if (slash != std::string::npos) t[slash] = '.';
  return t;
}

// A type as the wire names it, ours: a ROS 2 name of one of the SDK's types, or of ROS 2's
// standard types a port may carry (cdr/ros2_std_types.hpp), back to it.
std::string our_type(const std::string& wire) {
  std::size_t n = 0;
  const msgs::TypeEntry* types = msgs::all_types(&n);
  for (std::size_t i = 0; i < n; ++i)
    if (wire_type(types[i].name, true) == wire) return types[i].name;
  for (const std::string& standard : cdr::ros2_standard_types())
    if (wire_type(standard, true) == wire) return standard;
  return wire;
}

void on_signal(int) { g_interrupt = true; }

struct Heard {
  std::mutex m;
  std::condition_variable cv;
  std::map<std::string, std::string> writers;  // node.port → type
  std::map<std::string, std::string> wire;     // node.port → "DDS topic, DDS type" where ROS 2 names them
};

// Waits until `done` (checked under the lock) or the deadline or Ctrl-C.
template <class Done>
bool wait_for(Heard& h, Clock::time_point deadline, Done done) {
  std::unique_lock<std::mutex> l(h.m);
  while (!done() && !g_interrupt) {
    if (Clock::now() >= deadline) return false;
    h.cv.wait_for(l, std::min<Clock::duration>(deadline - Clock::now(), std::chrono::milliseconds(100)));
  }
  return done();
}

// A bad request: said on stderr, exit 2.
int refuse(const std::string& what) {
  std::fprintf(stderr, "error: %s\n", what.c_str());
  return 2;
}

// The verb and (echo, hz) the topic: 0 when fine, else the exit code.
int check_request(const TopicOptions& o) {
  if (o.verb != "list" && o.verb != "echo" && o.verb != "hz") return refuse("topic " + o.verb + ": unknown (topic list | echo NODE.PORT | hz NODE.PORT)");
  if (o.verb != "list") {
    const auto dot = o.topic.find('.');
    if (o.topic.empty() || dot == std::string::npos || dot == 0 || dot + 1 == o.topic.size())
      return refuse("topic " + o.verb + ": expected a topic NODE.PORT" + (o.topic.empty() ? "" : ", not '" + o.topic + "'"));
  }
  return 0;
}

// The participant's settings: every writer it hears of goes into `heard`.
DdsSettings listener_settings(const TopicOptions& o, Heard& heard) {
  DdsSettings ds;
  ds.domain = o.domain;
  if (!o.security.empty()) ds.security = security::security_identity(o.security, o.identity.empty() ? security::kObserver : o.identity);
  ds.ros2_naming = o.ros2_naming;
  ds.on_writer = [&heard](const std::string& topic, const std::string& type) {
    std::lock_guard<std::mutex> l(heard.m);
    heard.writers[ours(topic)] = our_type(type);
    if (our_type(type) != type) heard.wire[ours(topic)] = topic + ", " + type;
    heard.cv.notify_all();
  };
  return ds;
}

// `topic list`: every writer heard while it listens, with its type.
int list_topics(const TopicOptions& o, Heard& heard) {
  // An authenticated peer takes longer to be heard (the handshake first): 1.5 to 2 s here.
  const double listen = o.duration.value_or(o.security.empty() ? 2.0 : 4.0);
  wait_for(heard, Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(listen)), [] { return false; });
  std::lock_guard<std::mutex> l(heard.m);
  if (heard.writers.empty()) {
    std::fprintf(stderr, "error: no writer heard on domain %d within %.1f s (is a graph running there? --domain N)\n", o.domain, listen);
    return 1;
  }
  std::size_t w = 5;
  for (const auto& [t, type] : heard.writers) w = std::max(w, t.size());
  for (const auto& [t, type] : heard.writers) {
    const auto wire = heard.wire.find(t);  // ROS 2's names: as they are on the wire too
    std::printf("%-*s  %s%s\n", static_cast<int>(w), t.c_str(), type.c_str(), wire == heard.wire.end() ? "" : ("  (ROS 2 names: " + wire->second + ")").c_str());
  }
  return 0;
}

// What echo and hz have heard of the topic's samples (under `m`: the reader's thread writes it).
struct Listened {
  std::mutex m;
  long samples = 0;
  std::vector<double> arrivals;  // hz: seconds since the first
  Clock::time_point t0;
  std::string error;  // the first sample that did not decode
};

// Until --duration, --count or Ctrl-C; hz: a line a second while it listens.
void listen_for_samples(const TopicOptions& o, Listened& listened) {
  const auto until = o.duration ? listened.t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(*o.duration))
                                : Clock::time_point::max();
  const std::vector<double>& arrivals = listened.arrivals;
  std::size_t reported = 0;
  while (!g_interrupt && Clock::now() < until) {
    {
      std::lock_guard<std::mutex> l(listened.m);
      if (o.count && listened.samples >= *o.count) break;
      if (o.verb == "hz" && arrivals.size() > reported + 1 && arrivals.back() - arrivals[reported] >= 1.0) {
        const double span = arrivals.back() - arrivals[reported];
        std::printf("%s: %.2f Hz (%zu samples in %.2f s)\n", o.topic.c_str(), static_cast<double>(arrivals.size() - 1 - reported) / span,
                    arrivals.size() - reported, span);
        std::fflush(stdout);
        reported = arrivals.size() - 1;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

// The end of echo and hz: an error, or (hz) the rate over everything heard. Called with the reader closed.
int conclude(const TopicOptions& o, Listened& listened) {
  std::lock_guard<std::mutex> l(listened.m);
  if (!listened.error.empty()) {
    std::fprintf(stderr, "error: %s: a sample did not decode by its IDL: %s\n", o.topic.c_str(), listened.error.c_str());
    return 1;
  }
  if (listened.samples == 0) {
    std::fprintf(stderr, "error: %s: its writer was heard, but no sample came\n", o.topic.c_str());
    return 1;
  }
  const std::vector<double>& arrivals = listened.arrivals;
  if (o.verb == "hz" && arrivals.size() > 1) {
    std::vector<double> gaps;
    for (std::size_t i = 1; i < arrivals.size(); ++i) gaps.push_back(arrivals[i] - arrivals[i - 1]);
    std::sort(gaps.begin(), gaps.end());
    const double span = arrivals.back() - arrivals.front();
    std::printf("%s: %.2f Hz over %zu samples (%.2f s); intervals: median %.4f s, min %.4f s, max %.4f s\n", o.topic.c_str(),
                static_cast<double>(arrivals.size() - 1) / span, arrivals.size(), span, gaps[gaps.size() / 2], gaps.front(), gaps.back());
  }
  return 0;
}

// `topic echo | hz`: the topic's type from its writer's announcement, then its samples.
int follow_topic(const TopicOptions& o, Heard& heard, DdsTransport& dds) {
  const auto deadline = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(o.wait));
  if (!wait_for(heard, deadline, [&] { return heard.writers.count(o.topic) > 0; })) {
    std::fprintf(stderr, "error: no writer of %s on domain %d within %.1f s\n", o.topic.c_str(), o.domain, o.wait);
    return 1;
  }
  std::string type;
  {
    std::lock_guard<std::mutex> l(heard.m);
    type = heard.writers[o.topic];
  }
  const char* idl = idl_text(type);
  if (!find_wire_type(type) || !idl) return refuse(o.topic + ": type " + type + " is not one this build knows");
  SampleSerializer serializer(type);
  const cdr::CdrJson decoder(omgidl_schema(idl));
  Listened listened;
  listened.t0 = Clock::now();
  const auto dot = o.topic.find('.');
  dds.make_reader(topic_name(o.topic.substr(0, dot), o.topic.substr(dot + 1)), type, 100, [&](std::shared_ptr<const void> s) {
    std::lock_guard<std::mutex> l(listened.m);
    if (o.count && listened.samples >= *o.count) return;
    ++listened.samples;
    if (o.verb == "hz") {
      listened.arrivals.push_back(std::chrono::duration<double>(Clock::now() - listened.t0).count());
    } else {
      try {
        const auto b = serializer.serialize(s.get());
        std::printf("%s\n", decoder.decode(type, b.data, b.size).dump().c_str());
        std::fflush(stdout);
      } catch (const std::exception& e) {
        if (listened.error.empty()) listened.error = e.what();
      }
    }
    heard.cv.notify_all();
  });
  listen_for_samples(o, listened);
  dds.close_readers();
  return conclude(o, listened);
}

}  // namespace

int topic_command(const TopicOptions& o) {
  if (const int rc = check_request(o)) return rc;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  Heard heard;
  DdsTransport dds(listener_settings(o, heard));
  if (o.verb == "list") return list_topics(o, heard);
  return follow_topic(o, heard, dds);
}

}  // namespace brickyard::fw
