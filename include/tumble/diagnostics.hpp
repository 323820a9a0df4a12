#pragma once
/// Diagnostics: the suspect regimes a run met (energy gained in free flight, a step too large for
/// the spin rate, rotation drifting from unit length, a contact tolerance missed, the event cap
/// of a step hit, an adaptive step pinned at its minimum). The world and the integrators report
/// into a collector; run.json and the command line read it. The physics never prints.
///
/// Each code is kept once, at its first occurrence (its time and message), with a count of how
/// often it recurred: a warning names the first place to look and the fix.

#include <string>
#include <string_view>
#include <vector>

namespace tumble {

struct Diagnostic {
  std::string code;      ///< stable identifier, e.g. "free_flight_energy_gain"
  std::string severity;  ///< "warning"
  std::string message;   ///< what happened, with numbers
  double t_s = 0.0;      ///< simulated time of the first occurrence
  std::string fix;       ///< what to change, e.g. "use rk4 or dt <= 0.002 s"
  long occurrences = 1;
};

class Diagnostics {
 public:
  /// Records a warning; a code already recorded only counts one more occurrence.
  void warn(const std::string& code, double t_s, const std::string& message,
            const std::string& fix);
  /// When `code` is already recorded, counts one more occurrence and returns true: lets a hot
  /// loop skip composing a message it would not keep.
  bool recur(std::string_view code);
  bool has(std::string_view code) const;
  const std::vector<Diagnostic>& list() const { return list_; }
  bool empty() const { return list_.empty(); }

 private:
  std::vector<Diagnostic> list_;  // in order of first occurrence (deterministic)
};

}  // namespace tumble
