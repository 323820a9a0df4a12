// tumble's command line: parses, dispatches to one subcommand, and turns every failure into one
// message on stderr and the exit code SPEC.md gives (2 bad input, 3 environment / I/O).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "commands.hpp"
#include "tumble/error.hpp"
#include "version_text.hpp"

int main(int argc, char** argv) {
  using namespace tumble;
  // First of all: a Ctrl-C, SIGTERM, SIGHUP or SIGQUIT that comes while the command line is still being read
  // (a slow start on a busy machine) must end the run cleanly too, not kill it.
  cli::install_interrupt_handlers();
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
    std::fprintf(stderr, "tumble: error: %s\nRun 'tumble --help' for usage.\n", e.what());
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
