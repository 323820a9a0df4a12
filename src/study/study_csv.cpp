// study.csv: one line per row, every number in its shortest exact form (reads back bit-exact).
#include <string>

#include "tumble/study.hpp"
#include "tumble/trajectory_writer.hpp"

namespace tumble::study {
namespace {

// Booleans as words: a CSV reader (or a person) cannot mistake them for counts.
const char* word(bool b) {
  return b ? "true" : "false";
}

}  // namespace

const std::vector<std::string>& study_csv_columns() {
  // The first nine are SPEC.md's, in its order; the rest are the study's own.
  static const std::vector<std::string> columns = {"integrator",
                                                   "dt",
                                                   "tolerance",
                                                   "steps",
                                                   "evaluations",
                                                   "wall_s",
                                                   "error",
                                                   "pixel_error",
                                                   "energy_drift",
                                                   "orientation_error",
                                                   "impact_time_error",
                                                   "bounces",
                                                   "missed_impacts",
                                                   "extra_impacts",
                                                   "rejected_steps",
                                                   "status",
                                                   "trusted",
                                                   "indistinguishable",
                                                   "pareto",
                                                   "diagnostics"};
  return columns;
}

std::string study_csv(const StudyResult& result) {
  std::string out;
  for (const std::string& c : study_csv_columns()) out += (out.empty() ? "" : ",") + c;
  out += '\n';
  for (const RunRow& row : result.rows) {
    const RunSetting& s = row.setting;
    const bool adaptive = s.tolerance.has_value();
    std::vector<std::string> f;
    f.push_back(std::string(to_string(s.integrator)));
    f.push_back(format_double(s.dt_s));
    f.push_back(adaptive ? format_double(*s.tolerance) : "");
    if (row.diverged) {
      // A diverged run has no meaningful numbers: empty fields, not zeros.
      f.resize(study_csv_columns().size());
      f[15] = "diverged";
      f[16] = f[17] = f[18] = "false";
    } else {
      f.push_back(std::to_string(row.steps));
      f.push_back(std::to_string(row.evaluations));
      f.push_back(format_double(row.wall_s));
      f.push_back(format_double(row.error_m));
      f.push_back(format_double(row.pixel_error_px));
      f.push_back(format_double(row.energy_drift));
      f.push_back(format_double(row.orientation_error_rad));
      f.push_back(row.impact_time_error_s ? format_double(*row.impact_time_error_s) : "");
      f.push_back(std::to_string(row.bounces));
      f.push_back(std::to_string(row.missed_impacts));
      f.push_back(std::to_string(row.extra_impacts));
      f.push_back(adaptive ? std::to_string(row.rejected_steps) : "");
      f.push_back("ok");
      f.push_back(word(row.trusted));
      f.push_back(word(row.indistinguishable));
      f.push_back(word(row.pareto));
      std::string codes;
      for (const std::string& c : row.diagnostics) codes += (codes.empty() ? "" : ";") + c;
      f.push_back(codes);
    }
    std::string line;
    for (std::size_t i = 0; i < f.size(); ++i) line += (i ? "," : "") + f[i];
    out += line + '\n';
  }
  return out;
}

}  // namespace tumble::study
