// The output layer's libraries: OpenSSL's libcrypto (SHA-256; asked at run time) and
// nlohmann_json (header-only: the version compiled in).
#include "tumble/library_versions.hpp"

#include <openssl/crypto.h>
#include <openssl/opensslv.h>

#include <nlohmann/json.hpp>

namespace tumble::output {

LibraryVersions library_versions() {
  const std::string openssl = std::to_string(OPENSSL_version_major()) + "." +
                              std::to_string(OPENSSL_version_minor()) + "." +
                              std::to_string(OPENSSL_version_patch());
  const std::string json = std::to_string(NLOHMANN_JSON_VERSION_MAJOR) + "." +
                           std::to_string(NLOHMANN_JSON_VERSION_MINOR) + "." +
                           std::to_string(NLOHMANN_JSON_VERSION_PATCH);
  return {{"OpenSSL", runtime_version(openssl, OPENSSL_VERSION_STR)}, {"nlohmann_json", json}};
}

}  // namespace tumble::output
