#include "cli/topic_command.hpp"

#include "exec/executive.hpp"  // g_interrupt
#include "cdr/cdr_json.hpp"
#include "record/recorder.hpp"
#include "record/sample_serializer.hpp"
#include "security/security_files.hpp"
#include "transport/dds.hpp"

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

// "brickyard/node/port" → "node.port"; other DDS topics as they are.
std::string ours(const std::string& dds) {
  if (dds.rfind("brickyard/", 0) != 0) return dds;
  std::string t = dds.substr(10);
  const auto slash = t.find('/');
  if (slash != std::string::npos) t[slash] = '.';
  return t;
}

void on_signal(int) { g_interrupt = true; }

struct Heard {
  std::mutex m;
  std::condition_variable cv;
  std::map<std::string, std::string> writers;  // node.port → type
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

}  // namespace

int topic_command(const TopicOptions& o) {
  auto bad = [](const std::string& what) {
    std::fprintf(stderr, "error: %s\n", what.c_str());
    return 2;
  };
  if (o.verb != "list" && o.verb != "echo" && o.verb != "hz") return bad("topic " + o.verb + ": unknown (topic list | echo NODE.PORT | hz NODE.PORT)");
  if (o.verb != "list") {
    const auto dot = o.topic.find('.');
    if (o.topic.empty() || dot == std::string::npos || dot == 0 || dot + 1 == o.topic.size())
      return bad("topic " + o.verb + ": expected a topic NODE.PORT" + (o.topic.empty() ? "" : ", not '" + o.topic + "'"));
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  Heard heard;
  DdsSettings ds;
  ds.domain = o.domain;
  if (!o.security.empty()) ds.security = security::security_identity(o.security, o.identity.empty() ? security::kObserver : o.identity);
  ds.on_writer = [&heard](const std::string& topic, const std::string& type) {
    std::lock_guard<std::mutex> l(heard.m);
    heard.writers[ours(topic)] = type;
    heard.cv.notify_all();
  };
  DdsTransport dds(ds);

  if (o.verb == "list") {
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
    for (const auto& [t, type] : heard.writers) std::printf("%-*s  %s\n", static_cast<int>(w), t.c_str(), type.c_str());
    return 0;
  }

  // echo, hz: the topic's type from its writer's announcement.
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
  if (!msgs::find_type(type.c_str()) || !idl) return bad(o.topic + ": type " + type + " is not one this build knows");
  SampleSerializer serializer(type);
  const cdr::CdrJson decoder(omgidl_schema(idl));
  std::mutex out_m;
  long samples = 0;
  std::vector<double> arrivals;  // hz: seconds since the first
  const auto t0 = Clock::now();
  std::string error;
  const auto dot = o.topic.find('.');
  dds.make_reader(topic_name(o.topic.substr(0, dot), o.topic.substr(dot + 1)), type, 100, [&](std::shared_ptr<const void> s) {
    std::lock_guard<std::mutex> l(out_m);
    if (o.count && samples >= *o.count) return;
    ++samples;
    if (o.verb == "hz") {
      arrivals.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    } else {
      try {
        const auto b = serializer.serialize(s.get());
        std::printf("%s\n", decoder.decode(type, b.data, b.size).dump().c_str());
        std::fflush(stdout);
      } catch (const std::exception& e) {
        if (error.empty()) error = e.what();
      }
    }
    heard.cv.notify_all();
  });
  const auto until = o.duration ? t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(*o.duration))
                                : Clock::time_point::max();
  // hz: a line a second while it listens.
  std::size_t reported = 0;
  while (!g_interrupt && Clock::now() < until) {
    {
      std::lock_guard<std::mutex> l(out_m);
      if (o.count && samples >= *o.count) break;
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
  dds.close_readers();
  std::lock_guard<std::mutex> l(out_m);
  if (!error.empty()) {
    std::fprintf(stderr, "error: %s: a sample did not decode by its IDL: %s\n", o.topic.c_str(), error.c_str());
    return 1;
  }
  if (samples == 0) {
    std::fprintf(stderr, "error: %s: its writer was heard, but no sample came\n", o.topic.c_str());
    return 1;
  }
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

}  // namespace brickyard::fw
