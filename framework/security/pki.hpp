#pragma once
// The few certificate-authority operations DDS security needs, on OpenSSL (Debian's libssl): a
// self-signed CA, identities it signs, and S/MIME signatures of the governance and permissions
// documents — what `openssl req`, `openssl ca` and `openssl smime -sign -text` would make, done
// in-process so `brickyard security init` needs no shell or openssl binary. No crypto of our own:
// every key, certificate and signature is OpenSSL's.
#include <string>

namespace brickyard::fw::pki {

// A key pair and its certificate, both PEM text.
struct Identity {
  std::string key_pem;   // PKCS#8 private key (ECDSA P-256)
  std::string cert_pem;  // X.509 v3
};

// A self-signed CA with subject `subject` ("CN=...,O=..."), valid `days` from one hour ago (a
// peer's clock a little behind still accepts it). Throws std::runtime_error with OpenSSL's reason.
Identity make_ca(const std::string& subject, int days);

// A participant's identity signed by `ca`: a leaf certificate (not a CA) with subject `subject`.
Identity make_identity(const Identity& ca, const std::string& subject, int days);

// `document` signed by `ca` as S/MIME (detached, text), what DDS security reads for governance
// and permissions.
std::string smime_sign(const Identity& ca, const std::string& document);

// Whether `signed_smime` verifies against `ca_cert_pem` (tests and `security init`'s own check).
bool smime_verify(const std::string& ca_cert_pem, const std::string& signed_smime);

// Why `cert_pem` would not authenticate against `ca_cert_pem` with `key_pem` (not signed by the
// CA, outside its validity, the key not its own, not PEM), or empty when it would.
std::string identity_problem(const std::string& ca_cert_pem, const std::string& cert_pem, const std::string& key_pem);

// The certificate's subject as RFC 2253 text ("CN=a,O=Brickyard"): how DDS names a participant's identity.
std::string subject_of(const std::string& cert_pem);

}  // namespace brickyard::fw::pki
