#include "tumble/diagnostics.hpp"

#include <algorithm>

namespace tumble {

void Diagnostics::warn(const std::string& code, double t_s, const std::string& message,
                       const std::string& fix) {
  const auto it =
      std::find_if(list_.begin(), list_.end(), [&](const Diagnostic& d) { return d.code == code; });
  if (it != list_.end()) {
    ++it->occurrences;
    return;
  }
  list_.push_back({code, "warning", message, t_s, fix, 1});
}

bool Diagnostics::recur(std::string_view code) {
  for (Diagnostic& d : list_)
    if (d.code == code) {
      ++d.occurrences;
      return true;
    }
  return false;
}

bool Diagnostics::has(std::string_view code) const {
  return std::any_of(list_.begin(), list_.end(),
                     [&](const Diagnostic& d) { return d.code == code; });
}

}  // namespace tumble
