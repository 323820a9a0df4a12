#include "partial_file.hpp"

#include "tumble/error.hpp"

namespace tumble {

void rename_into_place(const std::filesystem::path& temporary, const std::filesystem::path& final) {
  std::error_code ec;
  std::filesystem::rename(temporary, final, ec);
  if (ec)
    throw Error(ErrorKind::Environment, "cannot write \"" + final.string() + "\": " + ec.message());
}

}  // namespace tumble
