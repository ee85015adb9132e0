// Stopping a run cleanly on SIGINT or SIGTERM, and checkpoints on SIGUSR1 (afemp/interrupt.hpp).
#include "afemp/interrupt.hpp"

#include <csignal>
#include <cstdio>

namespace afemp::core {

namespace {

volatile std::sig_atomic_t received = 0;
volatile std::sig_atomic_t checkpoint_asked = 0;
struct sigaction previous_int, previous_term, previous_usr1;

extern "C" void on_signal(int signal) {
  received = signal;
  // The next one takes the default action: a second Ctrl-C stops at once.
  std::signal(signal, SIG_DFL);
}

extern "C" void on_checkpoint_signal(int) {
  checkpoint_asked = 1;
}

}  // namespace

InterruptHandler::InterruptHandler() {
  received = 0;
  struct sigaction action {};
  action.sa_handler = on_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, &previous_int);
  sigaction(SIGTERM, &action, &previous_term);
  checkpoint_asked = 0;
  struct sigaction usr1 {};
  usr1.sa_handler = on_checkpoint_signal;
  sigemptyset(&usr1.sa_mask);
  sigaction(SIGUSR1, &usr1, &previous_usr1);
}

InterruptHandler::~InterruptHandler() {
  sigaction(SIGINT, &previous_int, nullptr);
  sigaction(SIGTERM, &previous_term, nullptr);
  sigaction(SIGUSR1, &previous_usr1, nullptr);
}

bool take_checkpoint_request() {
  if (!checkpoint_asked) return false;
  checkpoint_asked = 0;
  return true;
}

int interrupt_signal() {
  return received;
}

const char* signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  if (signal == SIGUSR1) return "SIGUSR1";
  static char buf[32];
  std::snprintf(buf, sizeof buf, "signal %d", signal);
  return buf;
}

}  // namespace afemp::core
