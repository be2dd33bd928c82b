#include "security/pki.hpp"

#include <openssl/bio.h>
#include <openssl/err.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/pkcs7.h>
#include <openssl/rand.h>
#include <openssl/x509.h>
#include <openssl/x509v3.h>

#include <memory>
#include <stdexcept>

namespace brickyard::fw::pki {

namespace {

template <class T, void (*F)(T*)>
struct Free {
  void operator()(T* p) const { F(p); }
};
using Bio = std::unique_ptr<BIO, Free<BIO, BIO_free_all>>;
using Key = std::unique_ptr<EVP_PKEY, Free<EVP_PKEY, EVP_PKEY_free>>;
using Cert = std::unique_ptr<X509, Free<X509, X509_free>>;
using Pkcs7 = std::unique_ptr<PKCS7, Free<PKCS7, PKCS7_free>>;
using Store = std::unique_ptr<X509_STORE, Free<X509_STORE, X509_STORE_free>>;
using Ext = std::unique_ptr<X509_EXTENSION, Free<X509_EXTENSION, X509_EXTENSION_free>>;

[[noreturn]] void fail(const std::string& what) {
  char buf[256] = "unknown reason";
  if (const unsigned long e = ERR_get_error()) ERR_error_string_n(e, buf, sizeof buf);
  ERR_clear_error();
  throw std::runtime_error(what + ": " + buf);
}

Bio mem(const std::string& text) {
  Bio b(BIO_new_mem_buf(text.data(), static_cast<int>(text.size())));
  if (!b) fail("OpenSSL could not allocate");
  return b;
}

std::string text_of(BIO* b) {
  char* p = nullptr;
  const long n = BIO_get_mem_data(b, &p);
  return std::string(p, static_cast<std::size_t>(n));
}

Key read_key(const std::string& pem) {
  Bio b = mem(pem);
  Key k(PEM_read_bio_PrivateKey(b.get(), nullptr, nullptr, nullptr));
  if (!k) fail("not a private key");
  return k;
}

Cert read_cert(const std::string& pem) {
  Bio b = mem(pem);
  Cert c(PEM_read_bio_X509(b.get(), nullptr, nullptr, nullptr));
  if (!c) fail("not a certificate");
  return c;
}

// "CN=a,O=b" into the name, attribute by attribute in the order given. The values are names this
// project checks (identifiers, "Brickyard"): no escaped commas to parse.
void set_name(X509_NAME* name, const std::string& subject) {
  std::size_t at = 0;
  while (at < subject.size()) {
    std::size_t comma = subject.find(',', at);
    if (comma == std::string::npos) comma = subject.size();
    const std::string part = subject.substr(at, comma - at);
    const std::size_t eq = part.find('=');
    if (eq == std::string::npos) throw std::runtime_error("subject part '" + part + "' is not TYPE=value");
    const std::string type = part.substr(0, eq), value = part.substr(eq + 1);
    if (!X509_NAME_add_entry_by_txt(name, type.c_str(), MBSTRING_UTF8, reinterpret_cast<const unsigned char*>(value.c_str()),
                                    static_cast<int>(value.size()), -1, 0))
      fail("subject " + part);
    at = comma + 1;
  }
}

void add_ext(X509* cert, X509* issuer, int nid, const char* value) {
  X509V3_CTX ctx;
  X509V3_set_ctx_nodb(&ctx);
  X509V3_set_ctx(&ctx, issuer, cert, nullptr, nullptr, 0);
  Ext e(X509V3_EXT_conf_nid(nullptr, &ctx, nid, value));
  if (!e || !X509_add_ext(cert, e.get(), -1)) fail("certificate extension");
}

Key new_key() {
  Key k(EVP_PKEY_Q_keygen(nullptr, nullptr, "EC", "P-256"));
  if (!k) fail("key generation");
  return k;
}

// A v3 certificate for `key`'s public half, subject `subject`, signed by `signer` (issuer
// `issuer`, null: self-signed).
Cert make_cert(EVP_PKEY* key, const std::string& subject, int days, X509* issuer, EVP_PKEY* signer, bool ca) {
  Cert c(X509_new());
  if (!c) fail("OpenSSL could not allocate");
  X509_set_version(c.get(), 2);
  unsigned char serial[16];
  if (RAND_bytes(serial, sizeof serial) != 1) fail("random serial");
  serial[0] &= 0x7f;  // a positive integer
  BIGNUM* bn = BN_bin2bn(serial, sizeof serial, nullptr);
  if (!bn || !BN_to_ASN1_INTEGER(bn, X509_get_serialNumber(c.get()))) fail("serial");
  BN_free(bn);
  X509_gmtime_adj(X509_getm_notBefore(c.get()), -3600);
  X509_time_adj_ex(X509_getm_notAfter(c.get()), days, 0, nullptr);
  X509_set_pubkey(c.get(), key);
  set_name(X509_get_subject_name(c.get()), subject);
  X509_set_issuer_name(c.get(), issuer ? X509_get_subject_name(issuer) : X509_get_subject_name(c.get()));
  X509* iss = issuer ? issuer : c.get();
  add_ext(c.get(), iss, NID_basic_constraints, ca ? "critical,CA:TRUE" : "critical,CA:FALSE");
  add_ext(c.get(), iss, NID_key_usage, ca ? "critical,keyCertSign,cRLSign,digitalSignature" : "critical,digitalSignature,keyAgreement");
  add_ext(c.get(), iss, NID_subject_key_identifier, "hash");
  if (!X509_sign(c.get(), signer, EVP_sha256())) fail("signing the certificate");
  return c;
}

Identity pem_of(EVP_PKEY* key, X509* cert) {
  Bio k(BIO_new(BIO_s_mem())), c(BIO_new(BIO_s_mem()));
  if (!k || !c || !PEM_write_bio_PrivateKey(k.get(), key, nullptr, nullptr, 0, nullptr, nullptr) || !PEM_write_bio_X509(c.get(), cert))
    fail("writing PEM");
  return {text_of(k.get()), text_of(c.get())};
}

}  // namespace

Identity make_ca(const std::string& subject, int days) {
  Key k = new_key();
  Cert c = make_cert(k.get(), subject, days, nullptr, k.get(), true);
  return pem_of(k.get(), c.get());
}

Identity make_identity(const Identity& ca, const std::string& subject, int days) {
  Key ca_key = read_key(ca.key_pem);
  Cert ca_cert = read_cert(ca.cert_pem);
  Key k = new_key();
  Cert c = make_cert(k.get(), subject, days, ca_cert.get(), ca_key.get(), false);
  return pem_of(k.get(), c.get());
}

std::string smime_sign(const Identity& ca, const std::string& document) {
  Key key = read_key(ca.key_pem);
  Cert cert = read_cert(ca.cert_pem);
  const int flags = PKCS7_DETACHED | PKCS7_TEXT;
  Bio in = mem(document);
  Pkcs7 p7(PKCS7_sign(cert.get(), key.get(), nullptr, in.get(), flags | PKCS7_STREAM));
  if (!p7) fail("signing the document");
  Bio out(BIO_new(BIO_s_mem()));
  Bio again = mem(document);
  if (!out || !SMIME_write_PKCS7(out.get(), p7.get(), again.get(), flags | PKCS7_STREAM)) fail("writing S/MIME");
  return text_of(out.get());
}

bool smime_verify(const std::string& ca_cert_pem, const std::string& signed_smime) {
  Cert ca = read_cert(ca_cert_pem);
  Store store(X509_STORE_new());
  if (!store || !X509_STORE_add_cert(store.get(), ca.get())) fail("certificate store");
  Bio in = mem(signed_smime);
  BIO* content = nullptr;
  Pkcs7 p7(SMIME_read_PKCS7(in.get(), &content));
  Bio content_owner(content);
  if (!p7) {
    ERR_clear_error();
    return false;
  }
  Bio out(BIO_new(BIO_s_mem()));
  const bool ok = PKCS7_verify(p7.get(), nullptr, store.get(), content, out.get(), PKCS7_TEXT) == 1;
  ERR_clear_error();
  return ok;
}

std::string identity_problem(const std::string& ca_cert_pem, const std::string& cert_pem, const std::string& key_pem) {
  Cert ca, cert;
  Key key;
  try {
    ca = read_cert(ca_cert_pem);
  } catch (const std::exception&) {
    return "the CA's file holds no PEM certificate";
  }
  try {
    cert = read_cert(cert_pem);
  } catch (const std::exception&) {
    return "the identity's cert.pem holds no PEM certificate";
  }
  try {
    key = read_key(key_pem);
  } catch (const std::exception&) {
    return "the identity's key.pem holds no PEM private key";
  }
  if (X509_check_private_key(cert.get(), key.get()) != 1) {
    ERR_clear_error();
    return "key.pem is not the key of cert.pem";
  }
  Store store(X509_STORE_new());
  if (!store || !X509_STORE_add_cert(store.get(), ca.get())) fail("certificate store");
  std::unique_ptr<X509_STORE_CTX, Free<X509_STORE_CTX, X509_STORE_CTX_free>> ctx(X509_STORE_CTX_new());
  if (!ctx || !X509_STORE_CTX_init(ctx.get(), store.get(), cert.get(), nullptr)) fail("certificate check");
  if (X509_verify_cert(ctx.get()) != 1) {
    const std::string why = X509_verify_cert_error_string(X509_STORE_CTX_get_error(ctx.get()));
    ERR_clear_error();
    return "cert.pem does not verify against the identity CA: " + why;
  }
  return {};
}

std::string subject_of(const std::string& cert_pem) {
  Cert c = read_cert(cert_pem);
  Bio out(BIO_new(BIO_s_mem()));
  if (!out || X509_NAME_print_ex(out.get(), X509_get_subject_name(c.get()), 0, XN_FLAG_RFC2253) < 0) fail("printing the subject");
  return text_of(out.get());
}

}  // namespace brickyard::fw::pki
