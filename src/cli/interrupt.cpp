// Ctrl-C and SIGTERM end a run cleanly: the handler only raises a flag; the frame and sample
// loops check it and throw, so every temporary output is removed on the way out (the final
// names are never touched) and the encoder thread is joined.
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
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
}

bool interrupted() {
  return g_signal != 0;
}

void throw_if_interrupted() {
  if (g_signal != 0) throw Interrupted(static_cast<int>(g_signal));
}

}  // namespace tumble::cli
