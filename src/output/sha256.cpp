// SHA-256 through OpenSSL's libcrypto (EVP digest API): the system's maintained, audited
// implementation instead of a hand-written one. Digests are unchanged (FIPS 180-4).
#include "tumble/sha256.hpp"

#include <openssl/evp.h>

#include <fstream>
#include <memory>
#include <vector>

#include "tumble/error.hpp"

namespace tumble {
namespace {

struct FreeDigestContext {
  void operator()(EVP_MD_CTX* ctx) const { EVP_MD_CTX_free(ctx); }
};

/// One SHA-256 computation; the EVP_MD_CTX is freed on every path, exceptions included.
class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new()) {
    // Only allocation or a libcrypto without SHA-256 can fail here: an environment failure.
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1) fail("initialise");
  }
  void update(const void* data, std::size_t n) {
    if (EVP_DigestUpdate(ctx_.get(), data, n) != 1) fail("update");
  }
  std::string hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    if (EVP_DigestFinal_ex(ctx_.get(), digest, &length) != 1) fail("finish");
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out;
    out.reserve(2 * length);
    for (unsigned int i = 0; i < length; ++i) {
      out += kDigits[digest[i] >> 4];
      out += kDigits[digest[i] & 0xf];
    }
    return out;
  }

 private:
  [[noreturn]] static void fail(const char* stage) {
    throw Error(ErrorKind::Environment, std::string("OpenSSL could not ") + stage + " a SHA-256");
  }
  std::unique_ptr<EVP_MD_CTX, FreeDigestContext> ctx_;
};

}  // namespace

std::string sha256_hex(std::string_view bytes) {
  Sha256 h;
  h.update(bytes.data(), bytes.size());
  return h.hex();
}

std::string sha256_file_hex(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorKind::Environment, "cannot read \"" + path.string() + "\"");
  Sha256 h;
  std::vector<char> buffer(1 << 16);
  while (in.read(buffer.data(), static_cast<long>(buffer.size())) || in.gcount() > 0)
    h.update(buffer.data(), static_cast<std::size_t>(in.gcount()));
  if (in.bad()) throw Error(ErrorKind::Environment, "cannot read \"" + path.string() + "\"");
  return h.hex();
}

}  // namespace tumble
