#include "tumble/job_folder.hpp"

#include <charconv>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "tumble/atomic_file.hpp"
#include "tumble/error.hpp"

namespace tumble::sweep {
namespace {

namespace fs = std::filesystem;

std::optional<std::string> read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// An output's path as run.json gives it, made relative to the job folder.
std::string in_folder(const std::string& path, const fs::path& dir) {
  const fs::path relative = fs::path(path).lexically_relative(dir);
  return relative.empty() || relative.begin()->string() == ".." ? fs::path(path).filename().string()
                                                                : relative.string();
}

RunFacts facts_of(const nlohmann::json& j, const fs::path& dir) {
  RunFacts f;
  const nlohmann::json& physics = j.at("physics");
  f.energy_start_J = physics.at("energy_start_J").get<double>();
  f.energy_end_J = physics.at("energy_end_J").get<double>();
  f.contacts = physics.at("contacts").get<long>();
  f.wall_s = j.at("wall_time").at("total_s").get<double>();
  for (const nlohmann::json& output : j.at("outputs"))
    f.outputs.emplace_back(in_folder(output.at("path").get<std::string>(), dir),
                           output.at("sha256").get<std::string>());
  return f;
}

}  // namespace

std::string_view to_string(JobState state) {
  switch (state) {
    case JobState::Missing:
      return "missing";
    case JobState::Stale:
      return "stale";
    case JobState::Finished:
      return "finished";
    case JobState::Failed:
      return "failed";
  }
  return "missing";
}

JobRecord read_job_folder(const fs::path& dir, std::string_view scene_sha256,
                          std::string_view version) {
  JobRecord record;
  if (const std::optional<std::string> run = read_text(dir / "run.json")) {
    record.state = JobState::Stale;
    // A run.json that does not parse, or lacks a field, is another program's: stale, rerun.
    const nlohmann::json j = nlohmann::json::parse(*run, nullptr, /*allow_exceptions=*/false);
    try {
      if (j.is_object() && j.at("scene").at("sha256").get<std::string>() == scene_sha256 &&
          j.at("tool").at("version").get<std::string>() == version) {
        record.facts = facts_of(j, dir);
        record.complete = true;
        record.state = JobState::Finished;
      }
    } catch (const nlohmann::json::exception&) {
      record.facts.reset();
    }
  }
  if (const std::optional<std::string> error = read_text(dir / "error.txt")) {
    // A failure is a failure with or without a run.json (--strict writes both).
    {
      int code = 3;
      const std::size_t eol = error->find('\n');
      const std::string first = error->substr(0, eol);
      if (first.starts_with("exit "))
        std::from_chars(first.data() + 5, first.data() + first.size(), code);
      record.state = JobState::Failed;
      record.exit_code = code;
      record.error = eol == std::string::npos ? "" : error->substr(eol + 1);
      while (!record.error.empty() && record.error.back() == '\n') record.error.pop_back();
    }
  }
  return record;
}

void write_error_file(const fs::path& dir, int exit_code, std::string_view message) {
  write_file_atomically(dir / "error.txt",
                        "exit " + std::to_string(exit_code) + "\n" + std::string(message) + "\n");
}

void clear_job_results(const fs::path& dir) {
  for (const char* name : {"run.json", "error.txt"}) {
    std::error_code ec;
    fs::remove(dir / name, ec);
    if (ec)
      throw Error(ErrorKind::Environment,
                  "cannot remove \"" + (dir / name).string() + "\": " + ec.message());
  }
}

}  // namespace tumble::sweep
