#include "tumble/output_folder.hpp"

#include <fcntl.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <system_error>

#include "cannot_write.hpp"
#include "tumble/atomic_file.hpp"
#include "tumble/output_target.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kStagingStem = "tumble-run";

bool is_temporary_name(const std::string& name) {
  return name.size() > 9 && name.front() == '.' && name.ends_with(".partial");
}

// The staging folders of runs that were killed before they could remove them: only a holder of
// the folder's lock makes one, and this run holds it now, so every one found is a dead run's.
void remove_dead_runs_staging(const fs::path& dir) {
  // Built by appending: GCC 12 misreports `"." + string` as an overlapping memcpy (-Wrestrict).
  std::string prefix = ".";
  prefix.append(kStagingStem);
  prefix += '.';
  std::error_code ec;
  std::vector<fs::path> dead;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with(prefix) && is_temporary_name(name) && it->is_directory(ec))
      dead.push_back(it->path());
  }
  for (const fs::path& p : dead) fs::remove_all(p, ec);
}

const fs::path& locked(const fs::path& dir) {
  make_output_dir(dir);
  return dir;
}

}  // namespace

OutputFolder::OutputFolder(fs::path dir)
    : dir_(std::move(dir)), lock_(locked(dir_)), staging_([this] {
        remove_dead_runs_staging(dir_);
        return make_unique_temporary_folder(dir_, kStagingStem);
      }()) {}

OutputFolder::~OutputFolder() {
  std::error_code ignored;
  fs::remove_all(staging_, ignored);  // before the lock goes: no other run sees it half-removed
}

StagedOutput OutputFolder::file(const std::string& name) {
  output_target(dir_ / name);  // throws now for a folder in its place, not after the run
  entries_.push_back(Entry{name, false, {}});
  return {dir_ / name, staging_ / name};
}

StagedOutput OutputFolder::folder(const std::string& name,
                                  std::function<bool(const std::string&)> is_own) {
  entries_.push_back(Entry{name, true, std::move(is_own)});
  check_folder(entries_.back());
  std::error_code ec;
  fs::create_directory(staging_ / name, ec);
  if (ec) cannot_write(dir_ / name, ec.message());
  return {dir_ / name, staging_ / name};
}

void OutputFolder::check_folder(const Entry& entry) const {
  const fs::path target = dir_ / entry.name;
  struct stat st {};
  if (lstat(target.c_str(), &st) != 0) {
    if (errno == ENOENT) return;
    cannot_write(target, std::generic_category().message(errno));
  }
  if (S_ISLNK(st.st_mode))
    cannot_write(target, "it is a symbolic link; " + entry.name +
                     "/ is replaced as a whole at the end of a run, so it must be a folder");
  if (!S_ISDIR(st.st_mode)) cannot_write(target, "it is not a folder");
  std::error_code ec;
  for (fs::directory_iterator it(target, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const bool own =
        is_temporary_name(name) || (entry.is_own(name) && it->is_regular_file(ec) && !ec);
    if (!own)
      cannot_write(target, "it holds \"" + name + "\", which tumble did not write; " + entry.name +
                       "/ is replaced as a whole at the end of a run, so move that away or "
                       "choose another --out");
  }
  if (ec) cannot_write(target, ec.message());
}

void OutputFolder::place_folder(const Entry& entry) const {
  const fs::path target = dir_ / entry.name, staged = staging_ / entry.name;
  check_folder(entry);  // again: nothing that appeared since the start is deleted either
  if (std::rename(staged.c_str(), target.c_str()) == 0) return;  // there was none
  if (errno != EEXIST && errno != ENOTEMPTY) cannot_write(target, std::generic_category().message(errno));
  // One step: the new folder takes the old one's name, the old one the staged name. A reader
  // sees the old frames or the new, never a mix and never none.
  if (renameat2(AT_FDCWD, staged.c_str(), AT_FDCWD, target.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno != EINVAL && errno != ENOSYS) cannot_write(target, std::generic_category().message(errno));
    // A file system without the exchange: the old folder aside, the new one in, the old removed.
    const fs::path old = make_unique_temporary_folder(staging_, entry.name + "-old");
    if (std::rename(target.c_str(), old.c_str()) != 0)
      cannot_write(target, std::generic_category().message(errno));
    if (std::rename(staged.c_str(), target.c_str()) != 0) {
      const int error = errno;
      std::rename(old.c_str(), target.c_str());
      cannot_write(target, std::generic_category().message(error));
    }
    return;  // the old one goes with the staging folder
  }
  std::error_code ignored;
  fs::remove_all(staged, ignored);  // the previous run's frames, now under the staged name
}

void OutputFolder::commit() {
  for (const Entry& e : entries_) {
    if (e.folder)
      place_folder(e);
    else
      place_output(staging_ / e.name, output_target(dir_ / e.name));
  }
}

fs::path OutputFolder::staged_path_of(const fs::path& final_path) const {
  const fs::path relative = final_path.lexically_relative(dir_);
  if (relative.empty() || relative.begin()->string() == "..") return final_path;
  return staging_ / relative;
}

Error OutputFolder::in_final_names(const Error& e) const {
  std::string message = e.what();
  const std::string from = staging_.string(), to = dir_.string();
  for (std::size_t at = message.find(from); at != std::string::npos;
       at = message.find(from, at + to.size()))
    message.replace(at, from.size(), to);
  return Error(e.kind(), message, e.where());
}

}  // namespace tumble
