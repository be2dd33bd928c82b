// DDS security's documents and certificates (framework/security): what `brickyard security init`
// writes, checked without DDS; tests/cli/security.sh runs a secured graph and attacks it.
#include "graph/diagnostics.hpp"
#include "graph/resolve.hpp"
#include "test_registry.hpp"
#include "security/documents.hpp"
#include "security/pki.hpp"
#include "security/security_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

using namespace brickyard::fw;

namespace {

const Registry& registry() { return test::testing_plugins(); }

// src (process a) feeds sink (process b) and local (process b); tap (process a) feeds nothing.
const char* kSplit = R"({"clock": {"mode": "real"}, "nodes": {
    "src": {"plugin": "testing.scripted_source", "process": "a"},
    "tap": {"plugin": "testing.transform", "process": "a"},
    "sink": {"plugin": "testing.assert_sink", "process": "b"},
    "mid": {"plugin": "testing.transform", "process": "b"}},
  "wires": [{"from": "src.out", "to": ["sink.in", "tap.in"]}, {"from": "tap.out", "to": "mid.in"}]})";

std::string read(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

}  // namespace

TEST(Security, EachProcessMayWriteItsOutputsAndReadWhatCrossesIntoIt) {
  const GraphDecl g = parse_graph_text(kSplit, "g.json");
  const auto access = security::access_of(resolve_graph(g, registry()));
  ASSERT_EQ(access.size(), 3u);  // a, b, observer
  const auto& a = access.at("a");
  const auto& b = access.at("b");
  // Each says how its run ended to the other (exec/peer_ends.hpp); src feeds tap inside a: a reads
  // no wire.
  EXPECT_EQ(a.publish, (std::set<std::string>{"brickyard/src/out", "brickyard/tap/out", "brickyard_end/a"}));
  EXPECT_EQ(a.subscribe, (std::set<std::string>{"brickyard_end/b"}));
  EXPECT_EQ(b.publish, (std::set<std::string>{"brickyard/mid/out", "brickyard_end/b"}));
  EXPECT_EQ(b.subscribe, (std::set<std::string>{"brickyard/src/out", "brickyard/tap/out", "brickyard_end/a"}));
  const auto& o = access.at(security::kObserver);
  EXPECT_TRUE(o.publish.empty());
  EXPECT_EQ(o.subscribe, (std::set<std::string>{"brickyard/src/out", "brickyard/tap/out", "brickyard/mid/out"}));
}

TEST(Security, TheDocumentsSayWhatTheyGrant) {
  const std::string gov_sign = security::governance_xml(security::Protection::sign);
  EXPECT_NE(gov_sign.find("<allow_unauthenticated_participants>false</allow_unauthenticated_participants>"), std::string::npos);
  EXPECT_NE(gov_sign.find("<rtps_protection_kind>SIGN</rtps_protection_kind>"), std::string::npos);
  EXPECT_NE(gov_sign.find("<enable_write_access_control>true</enable_write_access_control>"), std::string::npos);
  const std::string gov_enc = security::governance_xml(security::Protection::encrypt);
  EXPECT_NE(gov_enc.find("<rtps_protection_kind>ENCRYPT</rtps_protection_kind>"), std::string::npos);
  EXPECT_EQ(gov_enc.find(">SIGN<"), std::string::npos);
  security::Access acc;
  acc.publish = {"brickyard/x/out"};
  const std::string perm = security::permissions_xml("p", "CN=p,O=Brickyard", acc, "2026-01-01T00:00:00", "2027-01-01T00:00:00");
  EXPECT_NE(perm.find("<subject_name>CN=p,O=Brickyard</subject_name>"), std::string::npos);
  EXPECT_NE(perm.find("<publish>\n          <topics>\n            <topic>brickyard/x/out</topic>"), std::string::npos);
  EXPECT_EQ(perm.find("<subscribe>"), std::string::npos);
  EXPECT_NE(perm.find("<default>DENY</default>"), std::string::npos);
}

TEST(Security, CertificatesAndSignaturesVerifyOnlyAgainstTheirCa) {
  const auto ca = pki::make_ca("CN=test CA,O=Brickyard", 30);
  const auto other = pki::make_ca("CN=attacker,O=Brickyard", 30);
  const auto id = pki::make_identity(ca, "CN=a,O=Brickyard", 30);
  EXPECT_EQ(pki::subject_of(id.cert_pem), "O=Brickyard,CN=a");
  EXPECT_EQ(pki::identity_problem(ca.cert_pem, id.cert_pem, id.key_pem), "");
  EXPECT_NE(pki::identity_problem(other.cert_pem, id.cert_pem, id.key_pem).find("does not verify against the identity CA"), std::string::npos);
  EXPECT_EQ(pki::identity_problem(ca.cert_pem, id.cert_pem, other.key_pem), "key.pem is not the key of cert.pem");
  EXPECT_EQ(pki::identity_problem(ca.cert_pem, "not a certificate", id.key_pem), "the identity's cert.pem holds no PEM certificate");
  const std::string doc = "<dds>grant</dds>\n";
  const std::string signed_doc = pki::smime_sign(ca, doc);
  EXPECT_TRUE(pki::smime_verify(ca.cert_pem, signed_doc));
  EXPECT_FALSE(pki::smime_verify(other.cert_pem, signed_doc));
  std::string tampered = signed_doc;
  tampered.replace(tampered.find("grant"), 5, "GRANT");
  EXPECT_FALSE(pki::smime_verify(ca.cert_pem, tampered));
  EXPECT_FALSE(pki::smime_verify(ca.cert_pem, "garbage"));
}

TEST(Security, InitWritesAFolderARunAccepts) {
  const auto dir = std::filesystem::temp_directory_path() / "brickyard_security_unit";
  std::filesystem::remove_all(dir);
  GraphDecl g = parse_graph_text(kSplit, "g.json");
  const auto r = security::init(resolve_graph(g, registry()), dir.string(), {});
  EXPECT_EQ(r.identities, (std::vector<std::string>{"a", "b", "observer"}));
  EXPECT_FALSE(r.reused_ca);
  EXPECT_EQ(std::filesystem::status(dir / "ca_key.pem").permissions() & std::filesystem::perms::all,
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  g.transport.security = dir.string();
  const DdsSecurity f = security::check_run(g, "b", {"a", "b"});
  EXPECT_EQ(f.cert, (dir / "b" / "cert.pem").string());
  EXPECT_NO_THROW(security::check_run(g, "", {"a", "b"}));
  // Again: the CA kept, the identities new; a's old key no longer fits its new certificate.
  const std::string old_key = read(dir / "a" / "key.pem");
  EXPECT_TRUE(security::init(resolve_graph(g, registry()), dir.string(), {}).reused_ca);
  std::ofstream(dir / "a" / "key.pem") << old_key;
  try {
    security::check_run(g, "a", {"a", "b"});
    FAIL() << "a stale key was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.diagnostics()[0].where, "g.json#/transport/security");
    EXPECT_NE(e.diagnostics()[0].message.find("key.pem is not the key of cert.pem"), std::string::npos);
  }
  std::filesystem::remove_all(dir);
}
