#pragma once
// MD5 for the tests only, by OpenSSL's EVP interface (a Debian library the framework already
// links): Ouster's digests of decoded fields are MD5 hex strings. Not for anything that needs a
// secure hash.
#include <openssl/evp.h>

#include <cstddef>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

namespace brickyard::drivers::test {

class Md5 {
 public:
  Md5() : ctx_(EVP_MD_CTX_new(), &EVP_MD_CTX_free) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_md5(), nullptr) != 1) throw std::runtime_error("OpenSSL: MD5 not available");
  }
  void update(const void* data, size_t size) { EVP_DigestUpdate(ctx_.get(), data, size); }
  // The digest as 32 lower-case hex digits (the hash is finished: update no more).
  std::string hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int n = 0;
    EVP_DigestFinal_ex(ctx_.get(), digest, &n);
    std::string out;
    char b[3];
    for (unsigned int i = 0; i < n; ++i) std::snprintf(b, sizeof b, "%02x", digest[i]), out += b;
    return out;
  }

 private:
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx_;
};

}  // namespace brickyard::drivers::test
