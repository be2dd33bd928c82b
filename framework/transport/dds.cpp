#include "transport/dds.hpp"
#include "transport/wire_types.hpp"

#include <cstdlib>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <brickyard/msgs/registry.hpp>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/DomainParticipantListener.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastdds/rtps/transport/shared_mem/SharedMemTransportDescriptor.h>
#include <fastrtps/utils/IPLocator.h>

#include <stdexcept>

namespace brickyard::fw {

using namespace eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::IPLocator;
using eprosima::fastrtps::rtps::Locator_t;

std::string topic_name(const std::string& node, const std::string& port) { return "brickyard/" + node + "/" + port; }

std::string wire_topic(const std::string& topic, bool ros2) { return ros2 ? "rt/" + topic : topic; }

std::string wire_type(const std::string& type, bool ros2) {
  if (!ros2) return type;
  const auto at = type.rfind("::");
  if (at == std::string::npos) return type;
  std::string package = type.substr(0, at);
  // A ROS 2 standard type ("nav_msgs::msg::Odometry", cdr/ros2_std_types.hpp) is in its package's msg module already.
  if (package.size() > 5 && package.compare(package.size() - 5, 5, "::msg") == 0) package.resize(package.size() - 5);
  for (std::size_t k; (k = package.find("::")) != std::string::npos;) package.replace(k, 2, "_");
  return package + "::msg::dds_::" + type.substr(at + 2) + "_";
}

namespace {
const eprosima::fastrtps::Duration_t kLease(0.5);  // a writer silent this long (its process gone) is lost
constexpr std::uint32_t kMaxParticipants = 120;     // participant ids on a domain's ports: 7410 + 2 id < 7400 + 250
}

struct WriterListener : DataWriterListener {
  std::atomic<int>* matched;
  void on_publication_matched(DataWriter*, const PublicationMatchedStatus& s) override {
    matched->store(s.current_count);
  }
};

// The names of the participants discovered, by GUID prefix: who a sample's writer is.
struct PeerNames {
  std::mutex m;
  std::map<eprosima::fastrtps::rtps::GuidPrefix_t, std::string> names;
  std::string of(const eprosima::fastrtps::rtps::GuidPrefix_t& p) {
    std::lock_guard<std::mutex> l(m);
    auto it = names.find(p);
    return it == names.end() ? std::string() : it->second;
  }
};

struct ReaderListener : DataReaderListener {
  TypeSupport type;
  std::shared_ptr<PeerNames> peers;
  WriterCheck check;
  std::mutex others_m;  // the listener may be called from more than one transport's thread
  std::set<eprosima::fastrtps::rtps::GUID_t> others;  // writers told of
  std::set<eprosima::fastrtps::rtps::GUID_t> heard;   // writers delivered, under others_m
  void note_heard(const InstanceHandle_t& h) {
    std::lock_guard<std::mutex> l(others_m);
    heard.insert(eprosima::fastrtps::rtps::iHandle2GUID(h));
  }
  // Whether a sample of this writer is delivered: one of the graph's, or accepted.
  bool from_ours(const InstanceHandle_t& h) {
    if (check.expected.empty()) return true;
    const auto guid = eprosima::fastrtps::rtps::iHandle2GUID(h);
    const std::string name = peers->of(guid.guidPrefix);
    if (name == check.expected) return true;
    bool first = false;
    {
      std::lock_guard<std::mutex> l(others_m);
      first = others.insert(guid).second;
    }
    if (first && check.other) {
      std::ostringstream g;
      g << guid;
      check.other(name.empty() ? "(unknown)" : name, g.str());
    }
    return check.accept_others;
  }
  std::function<void(std::shared_ptr<const void>)> deliver;
  std::function<void(bool)> liveliness;
  std::atomic<int>* matched = nullptr;
  // A writer whose liveliness lapsed (its process died or hangs), not one that left cleanly; or
  // one alive (new, or back).
  void on_liveliness_changed(DataReader*, const LivelinessChangedStatus& s) override {
    if (!liveliness) return;
    if (s.not_alive_count_change > 0) liveliness(false);
    if (s.alive_count_change > 0) liveliness(true);
  }
  void on_subscription_matched(DataReader*, const SubscriptionMatchedStatus& s) override { matched->store(s.current_count); }
  void on_data_available(DataReader* r) override {
    for (;;) {
      void* data = type->createData();
      SampleInfo info;
      if (r->take_next_sample(data, &info) != ReturnCode_t::RETCODE_OK) {
        type->deleteData(data);
        return;
      }
      if (!info.valid_data || !from_ours(info.publication_handle)) {
        type->deleteData(data);
        continue;
      }
      note_heard(info.publication_handle);
      TypeSupport t = type;
      deliver(std::shared_ptr<const void>(data, [t](const void* p) { t->deleteData(const_cast<void*>(p)); }));
    }
  }
};

struct DiscoveryListener : DomainParticipantListener {
  std::function<void(const std::string&, const std::string&)> on_writer;
  std::shared_ptr<PeerNames> peers;
  void on_participant_discovery(DomainParticipant*, eprosima::fastrtps::rtps::ParticipantDiscoveryInfo&& info) override {
    using S = eprosima::fastrtps::rtps::ParticipantDiscoveryInfo;
    std::lock_guard<std::mutex> l(peers->m);
    if (info.status == S::DISCOVERED_PARTICIPANT || info.status == S::CHANGED_QOS_PARTICIPANT)
      peers->names[info.info.m_guid.guidPrefix] = info.info.m_participantName.to_string();
  }
  void on_publisher_discovery(DomainParticipant*, eprosima::fastrtps::rtps::WriterDiscoveryInfo&& info) override {
    if (on_writer && info.status == eprosima::fastrtps::rtps::WriterDiscoveryInfo::DISCOVERED_WRITER)
      on_writer(info.info.topicName().to_string(), info.info.typeName().to_string());
  }
};

namespace {
// Lockstep QoS (DdsSettings::lockstep): every sample kept until acknowledged, whatever the depth.
template <class Qos>
void keep_all(Qos& q) {
  q.history().kind = KEEP_ALL_HISTORY_QOS;
  q.resource_limits().max_samples = 100000;
  q.resource_limits().max_instances = 1;
  q.resource_limits().max_samples_per_instance = 100000;
  q.reliability().max_blocking_time = eprosima::fastrtps::Duration_t(10.0);
}
}  // namespace

int DdsReader::writers_heard() const {
  std::lock_guard<std::mutex> l(listener_->others_m);
  return static_cast<int>(listener_->heard.size());
}

bool DdsWriter::write(const void* sample) { return writer_->write(const_cast<void*>(sample)); }

bool DdsWriter::wait_acked(double seconds) {
  return writer_->wait_for_acknowledgments(eprosima::fastrtps::Duration_t(seconds)) == ReturnCode_t::RETCODE_OK;
}

DdsTransport::DdsTransport(const DdsSettings& s) : secured_(s.security.on()), lockstep_(s.lockstep), ros2_naming_(s.ros2_naming) {
  auto* factory = DomainParticipantFactory::get_instance();
  // Profiles (FASTRTPS_DEFAULT_PROFILES_FILE) first, then read the defaults, then make them ours.
  factory->load_profiles();
  DomainParticipantQos q = factory->get_default_participant_qos();
  q.name(s.name.c_str());
  q.transport().use_builtin_transports = false;
  auto shm = std::make_shared<eprosima::fastdds::rtps::SharedMemTransportDescriptor>();
  shm->segment_size(s.shm_segment_bytes);
  if (s.shared_memory) q.transport().user_transports.push_back(shm);
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  for (const auto& i : s.interfaces) udp->interfaceWhiteList.push_back(i);
  q.transport().user_transports.push_back(udp);
  // Unicast discovery to the listed peers only: no multicast leaves the machine.
  // Under a supervisor every process it starts has a participant id of its own, a restarted one
  // too: the dead one's ports (files its peers still have mapped and send to) are never reused,
  // which would leave the new process deaf to its peers. The discovery's range of initial peers
  // spans them (Fast DDS's default is 4).
  if (const char* id = std::getenv("BRICKYARD_PARTICIPANT_ID"); id && *id) {
    q.wire_protocol().participant_id = std::atoi(id);
    shm->maxInitialPeersRange = udp->maxInitialPeersRange = kMaxParticipants;
  }
  auto& b = q.wire_protocol().builtin;
  b.initialPeersList.clear();
  b.metatrafficMulticastLocatorList.clear();
  for (const auto& p : s.peers) {
    Locator_t l;
    l.kind = LOCATOR_KIND_UDPv4;
    IPLocator::setIPv4(l, p);
    b.initialPeersList.push_back(l);
  }
  // No explicit unicast locators: Fast DDS then offers shared memory to peers on this host and
  // UDP only on the whitelisted interfaces (setting a UDP locator here would turn SHM off).
  if (s.security.on()) {
    // Fast DDS's builtin security plugins, configured by participant properties.
    auto& props = q.properties().properties();
    auto set = [&](const char* k, const std::string& v) { props.emplace_back(k, v); };
    set("dds.sec.auth.plugin", "builtin.PKI-DH");
    set("dds.sec.auth.builtin.PKI-DH.identity_ca", "file://" + s.security.identity_ca);
    set("dds.sec.auth.builtin.PKI-DH.identity_certificate", "file://" + s.security.cert);
    set("dds.sec.auth.builtin.PKI-DH.private_key", "file://" + s.security.key);
    set("dds.sec.access.plugin", "builtin.Access-Permissions");
    set("dds.sec.access.builtin.Access-Permissions.permissions_ca", "file://" + s.security.permissions_ca);
    set("dds.sec.access.builtin.Access-Permissions.governance", "file://" + s.security.governance);
    set("dds.sec.access.builtin.Access-Permissions.permissions", "file://" + s.security.permissions);
    set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
  }
  peers_ = std::make_shared<PeerNames>();
  discovery_ = std::make_unique<DiscoveryListener>();
  discovery_->on_writer = s.on_writer;
  discovery_->peers = peers_;
  participant_ = factory->create_participant(s.domain, q, discovery_.get(), StatusMask::none());
  if (!participant_)
    throw std::runtime_error("Fast DDS could not create a participant on domain " + std::to_string(s.domain) +
                             (s.security.on() ? " with the security files of " + s.security.cert +
                                                    " (a certificate, key or signed document that does not verify against the CA, or out of its validity)"
                                              : std::string()));
  publisher_ = participant_->create_publisher(PUBLISHER_QOS_DEFAULT);
  subscriber_ = participant_->create_subscriber(SUBSCRIBER_QOS_DEFAULT);
  if (!publisher_ || !subscriber_) throw std::runtime_error("Fast DDS could not create a publisher/subscriber");
}

DdsTransport::~DdsTransport() {
  close_readers();
  if (!participant_) return;
  for (auto& w : writers_) publisher_->delete_datawriter(w->writer_);
  writers_.clear();
  participant_->delete_contained_entities();
  DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

// The readers' counts stay readable for the run's summary; their DDS entities go.
void DdsTransport::close_readers() {
  for (auto& r : readers_) {
    if (!r->reader_) continue;
    r->reader_->set_listener(nullptr);
    subscriber_->delete_datareader(r->reader_);
    r->reader_ = nullptr;
  }
}

Topic* DdsTransport::topic(const std::string& name, const std::string& type_name) {
  const std::string dds_name = wire_topic(name, ros2_naming_), dds_type = wire_type(type_name, ros2_naming_);
  // create_topic returns null for a topic that exists: get-or-create.
  if (auto* d = participant_->lookup_topicdescription(dds_name)) return static_cast<Topic*>(d);
  if (!participant_->find_type(dds_type)) {
    const auto* entry = find_wire_type(type_name);
    if (!entry) throw std::runtime_error("no message type " + type_name);
    TypeSupport ts(entry->make());
    if (ts.register_type(participant_, dds_type) != ReturnCode_t::RETCODE_OK)
      throw std::runtime_error("cannot register type " + dds_type);
  }
  Topic* t = participant_->create_topic(dds_name, dds_type, TOPIC_QOS_DEFAULT);
  if (!t) throw std::runtime_error("cannot create topic " + dds_name + (secured_ ? " (its permissions name it neither to publish nor to subscribe)" : ""));
  return t;
}

DdsWriter* DdsTransport::make_writer(const std::string& topic_n, const std::string& type_name) {
  Topic* t = topic(topic_n, type_name);
  DataWriterQos q = DATAWRITER_QOS_DEFAULT;
  // Liveliness asserted for it every 0.1 s: a reader in another process knows within the lease
  // (kLease) that this process has died.
  q.liveliness().kind = AUTOMATIC_LIVELINESS_QOS;
  q.liveliness().lease_duration = kLease;
  q.liveliness().announcement_period = eprosima::fastrtps::Duration_t(0.1);
  q.reliability().kind = RELIABLE_RELIABILITY_QOS;
  q.history().kind = KEEP_LAST_HISTORY_QOS;
  q.history().depth = 8;
  q.durability().kind = VOLATILE_DURABILITY_QOS;
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  if (lockstep_) keep_all(q);
  auto w = std::make_unique<DdsWriter>();
  w->listener_ = std::make_unique<WriterListener>();
  w->listener_->matched = &w->matched_;
  w->writer_ = publisher_->create_datawriter(t, q, w->listener_.get());
  if (!w->writer_)
    throw std::runtime_error("cannot create a writer on " + wire_topic(topic_n, ros2_naming_) + (secured_ ? " (its permissions do not let this identity publish it)" : ""));
  writers_.push_back(std::move(w));
  return writers_.back().get();
}

DdsReader* DdsTransport::make_reader(const std::string& topic_n, const std::string& type_name, std::uint32_t depth,
                                     std::function<void(std::shared_ptr<const void>)> deliver, std::function<void(bool)> liveliness,
                                     WriterCheck check) {
  Topic* t = topic(topic_n, type_name);
  DataReaderQos q = DATAREADER_QOS_DEFAULT;
  q.liveliness().kind = AUTOMATIC_LIVELINESS_QOS;
  // On ROS 2's names a port's reader asks no lease, as ROS 2's default profile offers none: a
  // ROS 2 publisher with it would not match a reader asking 0.5 s (DDS matches an offered lease
  // only as short as the one asked). A writer's death is then the supervisor's to see, and its
  // input's staleness; the framework's own topics keep the lease (docs/ros2.md).
  const bool ros2_port = ros2_naming_ && topic_n.rfind("brickyard/", 0) == 0;
  q.liveliness().lease_duration = ros2_port ? eprosima::fastrtps::c_TimeInfinite : kLease;
  q.reliability().kind = RELIABLE_RELIABILITY_QOS;
  q.history().kind = KEEP_LAST_HISTORY_QOS;
  q.history().depth = static_cast<int32_t>(depth);
  q.durability().kind = VOLATILE_DURABILITY_QOS;
  q.endpoint().history_memory_policy = eprosima::fastrtps::rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
  if (lockstep_) keep_all(q);
  auto r = std::make_unique<DdsReader>();
  r->listener_ = std::make_unique<ReaderListener>();
  r->listener_->type = TypeSupport(find_wire_type(type_name)->make());
  r->listener_->deliver = std::move(deliver);
  r->listener_->liveliness = std::move(liveliness);
  r->listener_->peers = peers_;
  r->listener_->check = std::move(check);
  r->listener_->matched = &r->matched_;
  r->reader_ = subscriber_->create_datareader(t, q, r->listener_.get());
  if (!r->reader_)
    throw std::runtime_error("cannot create a reader on " + wire_topic(topic_n, ros2_naming_) + (secured_ ? " (its permissions do not let this identity subscribe to it)" : ""));
  readers_.push_back(std::move(r));
  return readers_.back().get();
}

}  // namespace brickyard::fw
