#pragma once
/// What a sweep job's folder (OUT/job_NNNNN/) says about it. run.json is written last and
/// atomically by the command, so its presence, for the same effective scene (its SHA-256) and
/// the same tumble version, means the job finished; error.txt (the exit code, then the message)
/// means it failed. Anything else (nothing, or a run.json of another scene or version) is a job
/// still to run.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tumble::sweep {

enum class JobState {
  Missing,   ///< never ran, or was interrupted: no run.json, no error.txt
  Stale,     ///< a run.json of another effective scene or tumble version
  Finished,  ///< run.json for this scene and version, no error
  Failed,    ///< error.txt (with or without a run.json: `--strict` writes both)
};
std::string_view to_string(JobState state);

/// The run's key figures, from run.json.
struct RunFacts {
  double energy_start_J = 0.0, energy_end_J = 0.0;
  long contacts = 0;
  double wall_s = 0.0;
  std::vector<std::pair<std::string, std::string>> outputs;  ///< path in the job folder, SHA-256
};

struct JobRecord {
  JobState state = JobState::Missing;
  bool complete = false;  ///< run.json matches: rerunning would give the same outputs (skip it)
  int exit_code = 0;      ///< failed: the exit code error.txt records
  std::string error;      ///< failed: its message
  std::optional<RunFacts> facts;  ///< when complete
};

/// Reads the folder of a job whose effective scene has the SHA-256 `scene_sha256`.
JobRecord read_job_folder(const std::filesystem::path& dir, std::string_view scene_sha256,
                          std::string_view version);

/// Records a failure in error.txt (atomically): "exit N" on the first line, then the message.
void write_error_file(const std::filesystem::path& dir, int exit_code, std::string_view message);

/// Removes run.json and error.txt before a job runs again, so an interruption leaves a folder
/// that says "not finished". Throws tumble::Error (Environment) when it cannot.
void clear_job_results(const std::filesystem::path& dir);

}  // namespace tumble::sweep
