// Ctrl-C (SIGINT), SIGTERM (a scheduler, a CI timeout), SIGHUP (the ssh session or terminal
// went away) and SIGQUIT (Ctrl-\) end a run cleanly: the handler only raises a flag; the frame
// and sample loops check it and throw, so every staged output is removed on the way out (the
// final names are never touched), the output folder's lock is released and the encoder thread
// is joined; main() exits with 128 + the signal, as a shell reports a process the signal killed.
#include <csignal>

#include "commands.hpp"

namespace tumble::cli {
namespace {

volatile std::sig_atomic_t g_signal = 0;  // the one global: a signal handler can reach no other

extern "C" void on_signal(int signal) {
  g_signal = signal;
}

}  // namespace

void install_interrupt_handlers() {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
    struct sigaction previous {};
    sigaction(signal, nullptr, &previous);
    // Ignored when tumble started (nohup, a shell's background job ignoring SIGINT): the user
    // asked for the run to survive it, so it stays ignored.
    if (previous.sa_handler == SIG_IGN) continue;
    struct sigaction action {};
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    // Restarted system calls: a write interrupted by the signal completes rather than failing
    // as if the disk were full; the loops see the flag at the next frame or sample.
    action.sa_flags = SA_RESTART;
    sigaction(signal, &action, nullptr);
  }
}

bool interrupted() {
  return g_signal != 0;
}

void throw_if_interrupted() {
  if (g_signal != 0) throw Interrupted(static_cast<int>(g_signal));
}

}  // namespace tumble::cli
