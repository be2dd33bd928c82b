// One-way latency through Brickyard ports against raw Fast DDS, measured in the same run.
//   same process: publish -> the subscriber's input has the sample (ours: pointer hand-off with
//                 the port's DDS writer present; raw: DataWriter::write -> listener take)
//   two processes: ping-pong over DDS, one-way = round trip / 2 (ours: ports + our transport;
//                 raw: plain DataWriter/DataReader with the same participant settings and QoS,
//                 DDS liveliness included; then raw without liveliness, what it costs)
// Exits 1 when a sample is lost (5 s without it) or arrives with another size than was sent.
// usage: bench_transport [--quick]
#include "exec/channels.hpp"
#include "transport/dds.hpp"

#include <brickyard/msgs/BlobPubSubTypes.h>
#include <brickyard/msgs/registry.hpp>

#include "dds_ping.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <thread>

using namespace brickyard;
using namespace brickyard::fw;
using namespace eprosima::fastdds::dds;
using namespace brickyard::bench;
using Clock = std::chrono::steady_clock;

namespace {

int g_domain = 0;

msgs::Blob make_blob(std::size_t bytes) {
  msgs::Blob b;
  b.data().assign(bytes, 7);
  return b;
}

// The raw endpoints' QoS is ours (transport/dds.cpp): RELIABLE, KEEP_LAST 8, and DDS liveliness,
// AUTOMATIC with a 0.5 s lease asserted every 0.1 s (how a process notices a dead peer), unless
// g_raw_liveliness is false: the last line, what liveliness itself costs.
bool g_raw_liveliness = true;

DataWriterQos writer_qos() { return our_writer_qos(g_raw_liveliness); }
DataReaderQos reader_qos() { return our_reader_qos(g_raw_liveliness); }

constexpr int kWarmup = 10;

// Sends n + kWarmup samples one at a time and times each until its arrival (or echo) is seen.
// `prepare` runs outside the timed region; `divisor` 2 turns a round trip into one way.
template <class Prepare, class Send>
Stats time_samples(int n, Arrival& arrival, double divisor, Prepare prepare, Send send) {
  std::vector<double> lat;
  for (int i = 0; i < n + kWarmup; ++i) {
    prepare();
    std::int64_t t0 = now_ns();
    send();
    std::int64_t t1 = arrival.wait_for(i + 1);
    if (i >= kWarmup) lat.push_back(static_cast<double>(t1 - t0) / divisor);
  }
  return stats(lat);
}

struct RawListener : DataReaderListener {
  msgs::Blob sample;
  Arrival arrival{"bench_transport"};
  void on_data_available(DataReader* r) override {
    SampleInfo info;
    while (r->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK)
      if (info.valid_data) arrival.mark(sample.data().size());
  }
};

// ---- same process ----
Stats raw_same_process(std::size_t bytes, int n) {
  auto* p = raw_participant(g_domain);
  TypeSupport ts(new msgs::BlobPubSubType());
  ts.register_type(p);
  auto* t = p->create_topic("raw_same", ts.get_type_name(), TOPIC_QOS_DEFAULT);
  auto* pub = p->create_publisher(PUBLISHER_QOS_DEFAULT);
  auto* sub = p->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  RawListener l;
  l.arrival.bytes = bytes;
  auto* r = sub->create_datareader(t, reader_qos(), &l);
  auto* w = pub->create_datawriter(t, writer_qos());
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  msgs::Blob msg = make_blob(bytes);
  Stats st = time_samples(n, l.arrival, 1.0, [] {}, [&] { w->write(&msg); });
  sub->delete_datareader(r);
  p->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(p);
  return st;
}

const char* const kBlob = "brickyard::msgs::Blob";

DdsSettings bench_settings() {
  DdsSettings s;
  s.domain = g_domain;
  return s;
}

// Our side of a measurement: an output port with its DDS writer, and an input that marks each
// arrival. The message is built outside the timed region, like the raw case, and moved in.
struct OursPorts {
  explicit OursPorts(const std::string& out_topic) : transport(bench_settings()) {
    out.writer = transport.make_writer(out_topic, kBlob);
    in.on_arrival = [this](const std::string&) {
      for (const auto& sample : in.take()) arrival.mark(static_cast<const msgs::Blob*>(sample.get())->data().size());
    };
  }
  Stats time(int n, std::size_t bytes, double divisor) {
    arrival.bytes = bytes;
    msgs::Blob msg;
    return time_samples(n, arrival, divisor, [&] { msg = make_blob(bytes); },
                        [&] { out.publish(std::make_shared<const msgs::Blob>(std::move(msg))); });
  }
  DdsTransport transport;
  OutputPort out{"out", kBlob};
  InputQueue in{"in", kBlob, 8, true};
  Arrival arrival{"bench_transport"};
};

Stats ours_same_process(std::size_t bytes, int n) {
  OursPorts ours("brickyard/bench/out");
  ours.out.local.push_back(&ours.in);
  return ours.time(n, bytes, 1.0);
}

// ---- two processes: ping-pong, the child echoes ----
// The echo side is this program started again (fork + exec): a child forked from a process that
// has used Fast DDS inherits its threads' state and cannot discover anything.
pid_t spawn_echo(const char* kind, std::size_t bytes, int total) {
  pid_t child = fork();
  if (child == 0) {
    std::string b = std::to_string(bytes), t = std::to_string(total), d = std::to_string(g_domain);
    execl("/proc/self/exe", "bench_transport", "--echo", kind, b.c_str(), t.c_str(), d.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return child;
}

void raw_echo_child(std::size_t bytes, int total) {
  auto* p = raw_participant(g_domain);
  TypeSupport ts(new msgs::BlobPubSubType());
  ts.register_type(p);
  auto* ping = p->create_topic("raw_ping", ts.get_type_name(), TOPIC_QOS_DEFAULT);
  auto* pong = p->create_topic("raw_pong", ts.get_type_name(), TOPIC_QOS_DEFAULT);
  auto* w = p->create_publisher(PUBLISHER_QOS_DEFAULT)->create_datawriter(pong, writer_qos());
  RawListener l;
  l.arrival.bytes = bytes;
  p->create_subscriber(SUBSCRIBER_QOS_DEFAULT)->create_datareader(ping, reader_qos(), &l);
  for (int i = 0; i < total; ++i) {
    l.arrival.wait_for(i + 1);
    w->write(&l.sample);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  p->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(p);
}

Stats raw_two_process(std::size_t bytes, int n) {
  const int total = n + kWarmup;
  pid_t child = spawn_echo(g_raw_liveliness ? "raw" : "raw_without_liveliness", bytes, total);
  auto* p = raw_participant(g_domain);
  TypeSupport ts(new msgs::BlobPubSubType());
  ts.register_type(p);
  auto* ping = p->create_topic("raw_ping", ts.get_type_name(), TOPIC_QOS_DEFAULT);
  auto* pong = p->create_topic("raw_pong", ts.get_type_name(), TOPIC_QOS_DEFAULT);
  auto* w = p->create_publisher(PUBLISHER_QOS_DEFAULT)->create_datawriter(ping, writer_qos());
  RawListener l;
  l.arrival.bytes = bytes;
  auto* r = p->create_subscriber(SUBSCRIBER_QOS_DEFAULT)->create_datareader(pong, reader_qos(), &l);
  wait_matched(w, r);
  msgs::Blob msg = make_blob(bytes);
  Stats st = time_samples(n, l.arrival, 2.0, [] {}, [&] { w->write(&msg); });
  waitpid(child, nullptr, 0);
  p->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(p);
  return st;
}

// The echo node as the real clock runs one: an arrival wakes the node's own thread, which takes its
// input and republishes it (the raw echo likewise writes from its main thread, not from inside
// Fast DDS's listener, whose thread receives the next sample meanwhile).
void ours_echo_child(int total) {
  DdsTransport transport(bench_settings());
  OutputPort out("pong", kBlob);
  out.writer = transport.make_writer("brickyard/echo/pong", kBlob);
  InputQueue in("ping", kBlob, 8, true);
  std::mutex m;
  std::condition_variable cv;
  in.on_arrival = [&](const std::string&) {
    std::lock_guard<std::mutex> l(m);
    cv.notify_one();
  };
  transport.make_reader("brickyard/bench/ping", kBlob, 8, [&](std::shared_ptr<const void> smp) { in.push(std::move(smp)); });
  for (int echoed = 0; echoed < total;) {
    {
      std::unique_lock<std::mutex> l(m);
      if (!cv.wait_for(l, std::chrono::seconds(5), [&] { return static_cast<int>(in.received()) > echoed; })) break;
    }
    for (auto& smp : in.take()) out.publish(smp), ++echoed;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
}

Stats ours_two_process(std::size_t bytes, int n) {
  const int total = n + kWarmup;
  pid_t child = spawn_echo("ours", bytes, total);
  OursPorts ours("brickyard/bench/ping");
  ours.transport.make_reader("brickyard/echo/pong", kBlob, 8, [&](std::shared_ptr<const void> smp) { ours.in.push(std::move(smp)); });
  while (!ours.out.writer->has_remote_readers()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the reverse direction matches too
  Stats st = ours.time(n, bytes, 2.0);
  ours.transport.close_readers();
  waitpid(child, nullptr, 0);
  return st;
}

void row(const char* path, const char* size, Stats ours, Stats raw, const char* target) {
  std::printf("%-14s %-6s %10.2f %10.2f %10.2f %10.2f %8.2fx   %s\n", path, size, ours.median_us, ours.p99_us, raw.median_us,
              raw.p99_us, ours.median_us / raw.median_us, target);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 6 && std::strcmp(argv[1], "--echo") == 0) {
    g_domain = std::atoi(argv[5]);
    g_raw_liveliness = std::strcmp(argv[2], "raw_without_liveliness") != 0;
    if (std::strncmp(argv[2], "raw", 3) == 0) raw_echo_child(std::strtoul(argv[3], nullptr, 10), std::atoi(argv[4]));
    else ours_echo_child(std::atoi(argv[4]));
    return 0;
  }
  bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  g_domain = 200 + static_cast<int>(getpid() % 30);
  const int n_small = quick ? 200 : 2000, n_big = quick ? 30 : 200;
  std::size_t big = 2u << 20;
  const std::size_t small = 64;
  if (argc > 3 && std::strcmp(argv[2], "--big") == 0) big = std::strtoul(argv[3], nullptr, 10);
  std::fprintf(stderr, "bench_transport: DDS domain %d\n", g_domain);
  std::printf("one-way latency, microseconds (median, p99); ratio = ours / raw median\n");
  std::printf("%-14s %-6s %10s %10s %10s %10s %9s   %s\n", "path", "size", "ours med", "ours p99", "raw med", "raw p99",
              "ratio", "target");
  // Raw first, then ours, on each line (named variables: argument evaluation order is unspecified).
  Stats raw = raw_same_process(small, n_small), ours = ours_same_process(small, n_small);
  row("same process", "64 B", ours, raw, "ratio <= 2");
  raw = raw_same_process(big, n_big), ours = ours_same_process(big, n_big);
  row("same process", "2 MiB", ours, raw, "ours med <= 50 us");
  raw = raw_two_process(small, n_small), ours = ours_two_process(small, n_small);
  row("two processes", "64 B", ours, raw, "(reported)");
  raw = raw_two_process(big, n_big), ours = ours_two_process(big, n_big);
  row("two processes", "2 MiB", ours, raw, "ratio <= 1.2");
  // What DDS liveliness costs Fast DDS itself: the raw 2 MiB ping-pong again without it.
  g_raw_liveliness = false;
  const Stats bare = raw_two_process(big, n_big);
  std::printf("raw Fast DDS without liveliness, two processes, 2 MiB: median %.2f, p99 %.2f; liveliness costs raw %.2fx\n",
              bare.median_us, bare.p99_us, raw.median_us / bare.median_us);
  return 0;
}
