// Between two processes, what Fast DDS 2.9's data-sharing delivery with loaned samples costs
// against its serialized delivery, in the same run (issue 47's baseline): ping-pong, one-way =
// round trip / 2, for 64 B, 64 KiB, 2 MiB and 8 MiB.
//   serialized: a Blob (sequence<octet>) written and taken: serialized and copied on each side,
//               over the shared-memory transport (as bench_transport's raw rows);
//   loaned:     a plain, bounded sample of the size's class, loaned from the writer's pool and
//               filled there, taken as a loan by the reader (data-sharing: the reader maps the
//               writer's pool; nothing is serialized or copied), its echo likewise.
// Both with our QoS (RELIABLE, KEEP_LAST 8, AUTOMATIC liveliness 0.5 s) and our participant (SHM
// 16 MiB + UDP on 127.0.0.1). Exits 1 when a sample is lost (5 s) or arrives with another size.
// usage: bench_zero_copy [--quick]
#include <brickyard/msgs/Blob.h>
#include <brickyard/msgs/BlobPubSubTypes.h>
#include <fastdds/dds/core/LoanableSequence.hpp>
#include "dds_ping.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

using namespace eprosima::fastdds::dds;
using namespace brickyard::bench;
using Clock = std::chrono::steady_clock;

namespace {

int g_domain = 0;
constexpr int kWarmup = 10;

// A sample of a fixed capacity: how many bytes it carries, then the bytes. Plain (no pointer, its
// C++ layout is its wire layout) and bounded: what data-sharing's loans need.
template <std::size_t Cap> struct PlainBlob {
  std::uint32_t size;
  std::uint32_t seq;
  std::uint8_t data[Cap];
};

// Its type support: the used prefix behind the CDR encapsulation header when it must be
// serialized (a reader that cannot map the pool); plain for loans.
template <std::size_t Cap> class PlainBlobType : public TopicDataType {
 public:
  using Sample = PlainBlob<Cap>;
  PlainBlobType() {
    setName(("bench::PlainBlob_" + std::to_string(Cap)).c_str());
    m_typeSize = static_cast<std::uint32_t>(sizeof(Sample) + 4);
    m_isGetKeyDefined = false;
  }
  bool serialize(void* data, eprosima::fastrtps::rtps::SerializedPayload_t* payload) override {
    const auto* s = static_cast<const Sample*>(data);
    const std::uint32_t used = 8 + std::min<std::uint32_t>(s->size, Cap);
    if (payload->max_size < used + 4) return false;
    payload->data[0] = 0;
    payload->data[1] = 1;  // CDR, little endian
    payload->data[2] = payload->data[3] = 0;
    std::memcpy(payload->data + 4, s, used);
    payload->length = used + 4;
    return true;
  }
  bool deserialize(eprosima::fastrtps::rtps::SerializedPayload_t* payload, void* data) override {
    if (payload->length < 12 || payload->length - 4 > sizeof(Sample)) return false;
    std::memcpy(data, payload->data + 4, payload->length - 4);
    return true;
  }
  std::function<std::uint32_t()> getSerializedSizeProvider(void* data) override {
    return [data] { return 12 + std::min<std::uint32_t>(static_cast<Sample*>(data)->size, Cap); };
  }
  void* createData() override { return new Sample(); }
  void deleteData(void* data) override { delete static_cast<Sample*>(data); }
  bool getKey(void*, eprosima::fastrtps::rtps::InstanceHandle_t*, bool) override { return false; }
  bool is_bounded() const override { return true; }
  bool is_plain() const override { return true; }
  bool construct_sample(void* memory) const override {
    new (memory) Sample;
    return true;
  }
};

DataWriterQos writer_qos() { return our_writer_qos(true); }
DataReaderQos reader_qos() { return our_reader_qos(true); }

// How a path writes and takes its samples.
struct SerializedPath {
  using Type = brickyard::msgs::BlobPubSubType;
  brickyard::msgs::Blob msg, in;
  void prepare(std::size_t bytes) { msg.data().assign(bytes, 7); }
  bool write(DataWriter* w, std::size_t) { return w->write(&msg); }
  void take_all(DataReader* r, Arrival& a) {
    SampleInfo info;
    while (r->take_next_sample(&in, &info) == ReturnCode_t::RETCODE_OK)
      if (info.valid_data) a.mark(in.data().size());
  }
};

template <std::size_t Cap> struct LoanedPath {
  using Type = PlainBlobType<Cap>;
  using Sample = PlainBlob<Cap>;
  void* loan = nullptr;
  std::uint32_t seq = 0;
  // The producer fills the sample where it lies: in the writer's pool.
  bool fill(DataWriter* w, std::size_t bytes, bool touch) {
    if (w->loan_sample(loan) != ReturnCode_t::RETCODE_OK) return false;
    auto* s = static_cast<Sample*>(loan);
    s->size = static_cast<std::uint32_t>(bytes);
    s->seq = ++seq;
    if (touch) std::memset(s->data, 7, bytes);
    return true;
  }
  void prepare(std::size_t) {}
  bool write(DataWriter* w, std::size_t bytes) {
    if (!loan && !fill(w, bytes, false)) return false;
    const bool ok = w->write(loan);
    loan = nullptr;
    return ok;
  }
  void take_all(DataReader* r, Arrival& a) {
    LoanableSequence<Sample> data;
    SampleInfoSeq infos;
    while (r->take(data, infos) == ReturnCode_t::RETCODE_OK) {
      for (LoanableCollection::size_type i = 0; i < infos.length(); ++i)
        if (infos[i].valid_data) a.mark(data[i].size);
      r->return_loan(data, infos);
    }
  }
};

template <class Path> struct Listener : DataReaderListener {
  Path* path = nullptr;
  Arrival arrival{"bench_zero_copy"};
  void on_data_available(DataReader* r) override { path->take_all(r, arrival); }
};

// A process's endpoints: a writer on `out`, a reader on `in`.
template <class Path> struct Endpoints {
  DomainParticipant* p = nullptr;
  DataWriter* w = nullptr;
  DataReader* r = nullptr;
  Path path;
  Listener<Path> listener;
  Endpoints(const char* out, const char* in, std::size_t bytes) {
    p = raw_participant(g_domain);
    TypeSupport ts(new typename Path::Type());
    ts.register_type(p);
    auto* to = p->create_topic(out, ts.get_type_name(), TOPIC_QOS_DEFAULT);
    auto* from = p->create_topic(in, ts.get_type_name(), TOPIC_QOS_DEFAULT);
    w = p->create_publisher(PUBLISHER_QOS_DEFAULT)->create_datawriter(to, writer_qos());
    listener.path = &path;
    listener.arrival.bytes = bytes;
    r = p->create_subscriber(SUBSCRIBER_QOS_DEFAULT)->create_datareader(from, reader_qos(), &listener);
    if (!w || !r) {
      std::fprintf(stderr, "bench_zero_copy: could not create the endpoints\n");
      std::exit(1);
    }
  }
  ~Endpoints() {
    p->delete_contained_entities();
    DomainParticipantFactory::get_instance()->delete_participant(p);
  }
};

template <class Path> void echo(std::size_t bytes, int total) {
  Endpoints<Path> e("zc_pong", "zc_ping", bytes);
  for (int i = 0; i < total; ++i) {
    e.listener.arrival.wait_for(i + 1);
    e.path.prepare(bytes);
    if (!e.path.write(e.w, bytes)) std::exit(1);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
}

pid_t spawn_echo(const char* path, std::size_t bytes, int total) {
  const pid_t child = fork();
  if (child == 0) {
    const std::string b = std::to_string(bytes), t = std::to_string(total), d = std::to_string(g_domain);
    execl("/proc/self/exe", "bench_zero_copy", "--echo", path, b.c_str(), t.c_str(), d.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return child;
}

template <class Path> Stats ping(const char* name, std::size_t bytes, int n) {
  const int total = n + kWarmup;
  const pid_t child = spawn_echo(name, bytes, total);
  Stats st;
  {
    Endpoints<Path> e("zc_ping", "zc_pong", bytes);
    wait_matched(e.w, e.r);
    std::vector<double> lat;
    for (int i = 0; i < total; ++i) {
      e.path.prepare(bytes);
      if constexpr (requires { e.path.fill(e.w, bytes, true); }) {
        if (!e.path.fill(e.w, bytes, true)) std::exit(1);  // produced in the loan, outside the timing
      }
      const std::int64_t t0 = now_ns();
      if (!e.path.write(e.w, bytes)) {
        std::fprintf(stderr, "bench_zero_copy: %s: write failed\n", name);
        std::exit(1);
      }
      const std::int64_t t1 = e.listener.arrival.wait_for(i + 1);
      if (i >= kWarmup) lat.push_back(static_cast<double>(t1 - t0) / 2);
    }
    st = stats(lat);
    int status = 0;
    waitpid(child, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "bench_zero_copy: the %s echo failed\n", name);
      std::exit(1);
    }
  }
  return st;
}

// The size classes: a sample's capacity is its class's.
constexpr std::size_t k64 = 64, k64K = 64u << 10, k2M = 2u << 20, k8M = 8u << 20;

template <std::size_t Cap> Stats loaned(std::size_t bytes, int n) {
  return ping<LoanedPath<Cap>>(("loaned" + std::to_string(Cap)).c_str(), bytes, n);
}

int echo_main(const std::string& path, std::size_t bytes, int total) {
  if (path == "serialized") echo<SerializedPath>(bytes, total);
  else if (path == "loaned" + std::to_string(k64)) echo<LoanedPath<k64>>(bytes, total);
  else if (path == "loaned" + std::to_string(k64K)) echo<LoanedPath<k64K>>(bytes, total);
  else if (path == "loaned" + std::to_string(k2M)) echo<LoanedPath<k2M>>(bytes, total);
  else if (path == "loaned" + std::to_string(k8M)) echo<LoanedPath<k8M>>(bytes, total);
  else return 2;
  return 0;
}

void row(const char* size, Stats ser, Stats loan) {
  std::printf("%-8s %12.2f %12.2f %12.2f %12.2f %8.3fx\n", size, ser.median_us, ser.p99_us, loan.median_us, loan.p99_us,
              loan.median_us / ser.median_us);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 6 && std::strcmp(argv[1], "--echo") == 0) {
    g_domain = std::atoi(argv[5]);
    return echo_main(argv[2], std::strtoul(argv[3], nullptr, 10), std::atoi(argv[4]));
  }
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  g_domain = 200 + static_cast<int>(getpid() % 30);
  const int n_small = quick ? 200 : 2000, n_big = quick ? 30 : 200;
  std::fprintf(stderr, "bench_zero_copy: DDS domain %d\n", g_domain);
  std::printf("two processes, one-way latency, microseconds (round trip / 2); ratio = loaned / serialized median\n");
  std::printf("%-8s %12s %12s %12s %12s %9s\n", "size", "serial. med", "serial. p99", "loaned med", "loaned p99", "ratio");
  Stats s = ping<SerializedPath>("serialized", k64, n_small), l = loaned<k64>(k64, n_small);
  row("64 B", s, l);
  s = ping<SerializedPath>("serialized", k64K, n_small), l = loaned<k64K>(k64K, n_small);
  row("64 KiB", s, l);
  s = ping<SerializedPath>("serialized", k2M, n_big), l = loaned<k2M>(k2M, n_big);
  row("2 MiB", s, l);
  s = ping<SerializedPath>("serialized", k8M, n_big), l = loaned<k8M>(k8M, n_big);
  row("8 MiB", s, l);
  return 0;
}
