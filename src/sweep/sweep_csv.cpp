#include "tumble/sweep_csv.hpp"

#include <array>
#include <charconv>

namespace tumble::sweep {
namespace {

std::string number(double x) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), x);
  return std::string(buffer.data(), result.ptr);
}

// A TOML string without escapes reads better bare: render's "fxaa" is fxaa in a table.
std::string display(const std::string& value) {
  if (value.size() >= 2 && value.front() == '"' && value.back() == '"' &&
      value.find('\\') == std::string::npos)
    return value.substr(1, value.size() - 2);
  return value;
}

std::string header(const Plan& plan) {
  std::string line = "index";  // SPEC: "index and parameters"
  // One append at a time: GCC 12 warns falsely (-Wrestrict) about "," + std::string.
  for (const PlanKey* key : plan.keys()) line.append(",").append(csv_field(key->path));
  return line;
}

std::string parameters(const Job& job) {
  std::string line = std::to_string(job.index);
  for (const Parameter& p : job.parameters) line.append(",").append(csv_field(display(p.value)));
  return line;
}

}  // namespace

std::string job_list_header(const Plan& plan) {
  return header(plan);
}

std::string job_list_row(const Job& job) {
  return parameters(job);
}

std::string job_list_csv(const Plan& plan, const std::vector<Job>& jobs) {
  std::string csv = header(plan) + "\n";
  for (const Job& job : jobs) csv += parameters(job) + "\n";
  return csv;
}

std::string sweep_csv(const Plan& plan, const std::vector<Job>& jobs,
                      const std::vector<JobRecord>& records) {
  std::string csv = header(plan) +
                    ",status,exit_code,energy_start_J,energy_end_J,contacts,wall_s,outputs,error\n";
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const JobRecord& r = records[i];
    std::string line = parameters(jobs[i]);
    line.append(",").append(to_string(r.state)).append(",");
    if (r.state == JobState::Failed)
      line += std::to_string(r.exit_code);
    else if (r.state == JobState::Finished)
      line += "0";
    if (r.facts) {
      std::string outputs;
      for (const auto& [path, sha] : r.facts->outputs)
        outputs += (outputs.empty() ? "" : ";") + path + "=" + sha;
      for (const std::string& field :
           {number(r.facts->energy_start_J), number(r.facts->energy_end_J),
            std::to_string(r.facts->contacts), number(r.facts->wall_s), csv_field(outputs)})
        line.append(",").append(field);
    } else {
      line += ",,,,,";
    }
    line.append(",").append(csv_field(r.error));
    csv += line + "\n";
  }
  return csv;
}

}  // namespace tumble::sweep
