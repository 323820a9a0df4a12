#pragma once
/// The CSV tables of `tumble sweep` (RFC 4180 quoting): the job list of `--list`, and
/// sweep.csv of `--collect`, one row per job with its parameters, state and key figures.

#include <string>
#include <vector>

#include "tumble/csv_field.hpp"
#include "tumble/job_folder.hpp"
#include "tumble/sweep.hpp"

namespace tumble::sweep {

/// "job,<key path>,...", then one row per job: its index and each parameter's value (TOML text;
/// a string without its quotes).
std::string job_list_csv(const Plan& plan, const std::vector<Job>& jobs);
/// The job list's header line ("index,<key path>,..."), without its line break.
std::string job_list_header(const Plan& plan);
/// One job's row of the job list, without its line break.
std::string job_list_row(const Job& job);

/// sweep.csv: the job list's columns, then status, exit_code, energy_start_J, energy_end_J,
/// contacts, wall_s, outputs ("path=sha256" separated by ';'), error. `records[i]` is job i's.
std::string sweep_csv(const Plan& plan, const std::vector<Job>& jobs,
                      const std::vector<JobRecord>& records);

using tumble::csv_field;  // a CSV field, quoted where it must be (csv_field.hpp)

}  // namespace tumble::sweep
