// A plain Fast DDS subscriber: its own copy of the IDL-generated type, no Brickyard code.
// usage: raw_dds_subscriber DOMAIN TOPIC MIN_SAMPLES TIMEOUT_S
#include "ScalarPubSubTypes.h"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>

using namespace eprosima::fastdds::dds;

int main(int argc, char** argv) {
  if (argc != 5) return 2;
  int domain = std::atoi(argv[1]);
  const char* topic_name = argv[2];
  int want = std::atoi(argv[3]);
  double timeout = std::atof(argv[4]);

  DomainParticipantQos pq = PARTICIPANT_QOS_DEFAULT;
  // Loopback discovery, as Brickyard's own participant does.
  eprosima::fastrtps::rtps::Locator_t peer;
  peer.kind = LOCATOR_KIND_UDPv4;
  eprosima::fastrtps::rtps::IPLocator::setIPv4(peer, "127.0.0.1");
  pq.wire_protocol().builtin.initialPeersList.push_back(peer);
  auto* p = DomainParticipantFactory::get_instance()->create_participant(domain, pq);
  if (!p) return 1;
  TypeSupport type(new brickyard::msgs::ScalarPubSubType());
  type.register_type(p);
  Topic* t = p->create_topic(topic_name, type.get_type_name(), TOPIC_QOS_DEFAULT);
  Subscriber* s = p->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  DataReaderQos rq = DATAREADER_QOS_DEFAULT;
  rq.reliability().kind = RELIABLE_RELIABILITY_QOS;
  DataReader* r = s->create_datareader(t, rq);

  int got = 0;
  double last = -1;
  bool ordered = true;
  auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  while (got < want && std::chrono::steady_clock::now() < end) {
    brickyard::msgs::Scalar m;
    SampleInfo info;
    while (r->take_next_sample(&m, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) continue;
      if (got < 3 || got + 1 == want)
        std::printf("sample %d: stamp %lld ns, seq %u, value %g\n", got, static_cast<long long>(m.header().stamp_ns()),
                    m.header().seq(), m.value());
      ordered = ordered && m.value() > last;
      last = m.value();
      ++got;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  p->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(p);
  std::printf("received %d of %d samples on %s, increasing: %s\n", got, want, topic_name, ordered ? "yes" : "no");
  return got >= want && ordered ? 0 : 1;
}
