#pragma once
// What the DDS latency benches share (bench_transport, bench_zero_copy): the clock, a median and
// p99 of one-way times, a raw participant with Brickyard's settings, and one sample's arrival
// waited for by the timing thread.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace brickyard::bench {

inline std::int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Stats {
  double median_us = 0, p99_us = 0;
};
inline Stats stats(std::vector<double> ns) {
  std::sort(ns.begin(), ns.end());
  auto at = [&](double q) { return ns[std::min(ns.size() - 1, static_cast<std::size_t>(q * (ns.size() - 1) + 0.5))] / 1e3; };
  return {at(0.5), at(0.99)};
}

// A raw participant with the same settings as Brickyard's (SHM 16 MiB + UDP on 127.0.0.1).
inline eprosima::fastdds::dds::DomainParticipant* raw_participant(int domain) {
  using namespace eprosima::fastdds::dds;
  auto* f = DomainParticipantFactory::get_instance();
  f->load_profiles();
  DomainParticipantQos q = f->get_default_participant_qos();
  q.transport().use_builtin_transports = false;
  auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
  shm->segment_size(16u << 20);
  q.transport().user_transports.push_back(shm);
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  udp->interfaceWhiteList.push_back("127.0.0.1");
  q.transport().user_transports.push_back(udp);
  eprosima::fastrtps::rtps::Locator_t peer;
  peer.kind = LOCATOR_KIND_UDPv4;
  eprosima::fastrtps::rtps::IPLocator::setIPv4(peer, "127.0.0.1");
  q.wire_protocol().builtin.initialPeersList.push_back(peer);
  return f->create_participant(domain, q);
}

// The endpoints' QoS Brickyard's are made with (transport/dds.cpp): RELIABLE, KEEP_LAST 8,
// preallocated with realloc, and with `liveliness` AUTOMATIC with a 0.5 s lease asserted every
// 0.1 s (how a process notices a dead peer). Data-sharing left automatic.
template <class Q> void our_qos(Q& q, bool liveliness) {
  using namespace eprosima::fastdds::dds;
  if (liveliness) {
    q.liveliness().kind = AUTOMATIC_LIVELINESS_QOS;
    q.liveliness().lease_duration = eprosima::fastrtps::Duration_t(0.5);
  }
  q.reliability().kind = RELIABLE_RELIABILITY_QOS;
  q.history().kind = KEEP_LAST_HISTORY_QOS;
  q.history().depth = 8;
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
}
inline eprosima::fastdds::dds::DataWriterQos our_writer_qos(bool liveliness) {
  eprosima::fastdds::dds::DataWriterQos q = eprosima::fastdds::dds::DATAWRITER_QOS_DEFAULT;
  our_qos(q, liveliness);
  if (liveliness) q.liveliness().announcement_period = eprosima::fastrtps::Duration_t(0.1);
  return q;
}
inline eprosima::fastdds::dds::DataReaderQos our_reader_qos(bool liveliness) {
  eprosima::fastdds::dds::DataReaderQos q = eprosima::fastdds::dds::DATAREADER_QOS_DEFAULT;
  our_qos(q, liveliness);
  return q;
}

// Until a ping-pong's writer and reader have both matched (5 s at most), and then 0.2 s: each side
// sees its match on its own, and the echo's writer may not have matched our reader yet (its first
// echo would be lost).
inline void wait_matched(eprosima::fastdds::dds::DataWriter* w, eprosima::fastdds::dds::DataReader* r) {
  for (int k = 0; k < 500; ++k) {
    eprosima::fastdds::dds::PublicationMatchedStatus pm;
    eprosima::fastdds::dds::SubscriptionMatchedStatus sm;
    w->get_publication_matched_status(pm);
    r->get_subscription_matched_status(sm);
    if (pm.current_count > 0 && sm.current_count > 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
}

// Signals arrival of one sample to a waiting thread; a sample of another size than `bytes` ends
// the benchmark (what arrived is not what was timed), as does none within 5 s.
struct Arrival {
  const char* program = "bench";
  std::mutex m;
  std::condition_variable cv;
  std::int64_t t = 0;
  int count = 0;
  std::size_t bytes = 0;
  void mark(std::size_t arrived_bytes) {
    if (arrived_bytes != bytes) {
      std::fprintf(stderr, "%s: a sample of %zu bytes arrived, %zu were sent\n", program, arrived_bytes, bytes);
      std::exit(1);
    }
    const std::int64_t tn = now_ns();
    std::lock_guard<std::mutex> l(m);
    t = tn;
    ++count;
    cv.notify_one();
  }
  std::int64_t wait_for(int n) {
    std::unique_lock<std::mutex> l(m);
    if (!cv.wait_for(l, std::chrono::seconds(5), [&] { return count >= n; })) {
      std::fprintf(stderr, "%s: timeout waiting for sample %d\n", program, n);
      std::exit(1);
    }
    return t;
  }
};

}  // namespace brickyard::bench
