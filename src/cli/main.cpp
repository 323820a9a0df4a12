// tumble's command line: parses, dispatches to one subcommand, and turns every failure into one
// message on stderr and the exit code SPEC.md gives (2 bad input, 3 environment / I/O).
#include <CLI/CLI.hpp>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <cstdio>
#include <exception>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "commands.hpp"
#include "tumble/error.hpp"
#include "tumble/scene.hpp"
#include "version_text.hpp"

namespace {

// "unknown subcommand "rendr" (did you mean "render"?); the subcommands are render, ..." when
// the first word is neither an option nor a subcommand, else "": CLI11 alone would only say
// that a subcommand is required.
std::string unknown_subcommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  const std::string word = argv[1];
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == word) return "";
    names.push_back(sub->get_name());
  }
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  const std::optional<std::string> close =
      tumble::closest_match(word, std::vector<std::string_view>(names.begin(), names.end()));
  return "unknown subcommand \"" + word + "\"" +
         (close ? " (did you mean \"" + *close + "\"?)" : std::string()) +
         "; the subcommands are " + list;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tumble;
  // First of all: a Ctrl-C, SIGTERM, SIGHUP or SIGQUIT that comes while the command line is still
  // being read (a slow start on a busy machine) must end the run cleanly too, not kill it.
  cli::install_interrupt_handlers();
#if defined(__GLIBC__)
  // Freed memory stays with the process (up to 256 MiB at the heap's top, blocks up to 32 MiB
  // from the heap) rather than going back to the kernel at each free: an island's contact
  // solves allocate and free matrices of a few hundred kB many times a step, and glibc's
  // default (128 kB, then the largest freed) gave the pages back and faulted them in again each
  // time. A landing pile of 27 dice spent 36 % of its time so (page faults and TLB flushes, in
  // a virtual machine): 4.8 → 3.0 s. Peak memory is the same (50 → 52 MB).
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
#endif
  CLI::App app{"tumble: physically correct rigid-body clips, rendered headless", "tumble"};
  app.set_version_flag("--version", cli::version_text);
  app.require_subcommand(1);
  cli::RenderOptions render;
  cli::add_render_command(app, render);
  cli::SimulateOptions simulate;
  cli::add_simulate_command(app, simulate);
  cli::StudyOptions study;
  cli::add_study_command(app, study);
  cli::SweepOptions sweep;
  cli::add_sweep_command(app, sweep);
  cli::add_info_command(app);
  cli::DiffOptions diff;
  cli::add_diff_command(app, diff);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // CLI11 has its own exit codes (e.g. 105); a command-line mistake is bad input: 2.
    const std::string unknown = unknown_subcommand(app, argc, argv);
    std::fprintf(stderr, "tumble: error: %s\nRun 'tumble --help' for usage.\n",
                 unknown.empty() ? e.what() : unknown.c_str());
    return static_cast<int>(ErrorKind::BadInput);
  }

  try {
    if (app.got_subcommand("render")) return cli::run_render(render);
    if (app.got_subcommand("simulate")) return cli::run_simulate(simulate);
    if (app.got_subcommand("study")) return cli::run_study(study);
    if (app.got_subcommand("sweep")) return cli::run_sweep(sweep);
    if (app.got_subcommand("info")) return cli::run_info();
    if (app.got_subcommand("diff")) return cli::run_diff(diff);
  } catch (const cli::Interrupted& i) {
    std::fprintf(stderr, "tumble: interrupted; outputs left as they were\n");
    return 128 + i.signal;
  } catch (const Error& e) {
    std::fprintf(stderr, "tumble: error: %s\n", e.describe().c_str());
    return e.exit_code();
  } catch (const std::exception& e) {
    // Anything else is an environment failure (allocation, file system), never a crash.
    std::fprintf(stderr, "tumble: error: %s\n", e.what());
    return static_cast<int>(ErrorKind::Environment);
  }
  return 0;
}
