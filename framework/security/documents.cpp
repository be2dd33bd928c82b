#include "security/documents.hpp"

#include "transport/dds.hpp"

#include <sstream>

namespace brickyard::fw::security {

namespace {

std::string process_of(const NodeDecl& n) { return n.process.empty() ? kDefaultProcess : n.process; }

// Every domain id: a test or a second car runs the same graph with --domain N.
const char* kAllDomains = "<domains><id_range><min>0</min><max>232</max></id_range></domains>";

void topics(std::ostringstream& o, const char* verb, const std::set<std::string>& names) {
  if (names.empty()) return;
  o << "        <" << verb << ">\n          <topics>\n";
  for (const auto& t : names) o << "            <topic>" << t << "</topic>\n";
  o << "          </topics>\n        </" << verb << ">\n";
}

}  // namespace

std::map<std::string, Access> access_of(const ResolvedGraph& g) {
  std::map<std::string, Access> out;
  std::map<std::string, std::string> node_process;
  for (const auto& n : g.nodes) {
    const std::string p = process_of(*n.decl);
    node_process[n.decl->name] = p;
    Access& a = out[p];
    for (const auto& port : n.plugin->manifest.ports)
      if (port.direction == PortDirection::output) {
        a.publish.insert(topic_name(n.decl->name, port.name));
        out[kObserver].subscribe.insert(topic_name(n.decl->name, port.name));
      }
  }
  for (const auto& w : g.decl->wires) {
    const std::string& from = node_process[w.from.node];
    const std::string& to = node_process[w.to.node];
    if (from != to) out[to].subscribe.insert(topic_name(w.from.node, w.from.port));
  }
  // A split run on the sim clock keeps its processes in lockstep: each publishes its clock
  // records and reads every other's.
  // One on the real clock says how its run ended to the others (exec/peer_ends.hpp).
  if (g.processes.size() > 1) {
    const auto topic = g.decl->clock.sim ? clock_topic : end_topic;
    for (const auto& p : g.processes) {
      out[p].publish.insert(topic(p));
      for (const auto& q : g.processes)
        if (q != p) out[p].subscribe.insert(topic(q));
    }
  }
  if (g.decl->transport.ros2_naming)  // the names the topics have on the wire
    for (auto& [_, a] : out)
      for (auto* names : {&a.publish, &a.subscribe}) {
        std::set<std::string> named;
        for (const auto& t : *names) named.insert(wire_topic(t, true));
        *names = std::move(named);
      }
  return out;
}

std::string governance_xml(Protection p) {
  const bool enc = p == Protection::encrypt;
  const char* kind = enc ? "ENCRYPT" : "SIGN";
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       "<!-- Made by brickyard security init: who may join the domain and how its traffic is protected. -->\n"
       "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
       "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_governance.xsd\">\n"
       "  <domain_access_rules>\n    <domain_rule>\n      "
    << kAllDomains
    << "\n      <allow_unauthenticated_participants>false</allow_unauthenticated_participants>\n"
       "      <enable_join_access_control>true</enable_join_access_control>\n"
       "      <discovery_protection_kind>"
    << kind << "</discovery_protection_kind>\n      <liveliness_protection_kind>" << kind
    << "</liveliness_protection_kind>\n      <rtps_protection_kind>" << kind << "</rtps_protection_kind>\n      <topic_access_rules>\n";
  auto rule = [&](const std::string& expr, const char* data) {
    o << "        <topic_rule>\n          <topic_expression>" << expr
      << "</topic_expression>\n          <enable_discovery_protection>true</enable_discovery_protection>\n"
         "          <enable_liveliness_protection>true</enable_liveliness_protection>\n"
         "          <enable_read_access_control>true</enable_read_access_control>\n"
         "          <enable_write_access_control>true</enable_write_access_control>\n"
         "          <metadata_protection_kind>NONE</metadata_protection_kind>\n          <data_protection_kind>"
      << data << "</data_protection_kind>\n        </topic_rule>\n";
  };
  // Every RTPS message is signed, or encrypted, once, whole (rtps_protection_kind), commands with
  // the rest: the protection is the sending participant's, whose identity and permissions were
  // checked at discovery, and no authenticated process can write a topic its permissions deny.
  // Protecting each submessage (metadata) and each payload (data) again on top passed over every
  // LiDAR cloud two more times: encrypted, the split race cost 14.6 % more CPU (docs/security.md).
  // A topic's data signed on its own (data_protection_kind SIGN) delivered no sample at all with
  // Debian's Fast DDS 2.9 (the split main job's commands never reached the car).
  rule("*", "NONE");
  o << "      </topic_access_rules>\n    </domain_rule>\n  </domain_access_rules>\n</dds>\n";
  return o.str();
}

std::string permissions_xml(const std::string& identity, const std::string& subject, const Access& a,
                            const std::string& not_before, const std::string& not_after) {
  std::ostringstream o;
  o << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
       "<!-- Made by brickyard security init from the graph's wires: what identity '"
    << identity
    << "' may publish and subscribe. -->\n"
       "<dds xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
       "xsi:noNamespaceSchemaLocation=\"http://www.omg.org/spec/DDS-Security/20170801/omg_shared_ca_permissions.xsd\">\n"
       "  <permissions>\n    <grant name=\""
    << identity << "\">\n      <subject_name>" << subject << "</subject_name>\n      <validity>\n        <not_before>" << not_before
    << "</not_before>\n        <not_after>" << not_after << "</not_after>\n      </validity>\n";
  if (!a.publish.empty() || !a.subscribe.empty()) {
    o << "      <allow_rule>\n        " << kAllDomains << "\n";
    topics(o, "publish", a.publish);
    topics(o, "subscribe", a.subscribe);
    o << "      </allow_rule>\n";
  }
  o << "      <default>DENY</default>\n    </grant>\n  </permissions>\n</dds>\n";
  return o.str();
}

}  // namespace brickyard::fw::security
