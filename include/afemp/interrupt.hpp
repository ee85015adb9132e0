// Stopping a run cleanly on SIGINT (Ctrl-C) or SIGTERM, and checkpoints on SIGUSR1, for a
// program that runs as a command (`afemp run` does): the library installs nothing itself. The
// first SIGINT or SIGTERM asks the run to stop after the step it is in (a checkpoint, the final
// history row, frame and summary are written); it also restores the default action, so a second
// signal ends the process at once. SIGUSR1 asks for a checkpoint after the step and the run
// goes on. docs/restart.md.
#pragma once

namespace afemp::core {

/// Installs the handler for SIGINT, SIGTERM and SIGUSR1 while it lives, and clears the
/// requests; restores the previous handlers when destroyed. For SimulationOptions:
/// `stop_requested = [] { return afemp::interrupt_signal() != 0; }` and
/// `checkpoint_requested = afemp::take_checkpoint_request`.
class InterruptHandler {
 public:
  InterruptHandler();
  ~InterruptHandler();
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;
};

/// The signal that asked the run to stop (SIGINT or SIGTERM), or 0.
int interrupt_signal();
/// Whether SIGUSR1 came since the last call (the request is then cleared).
bool take_checkpoint_request();
/// "SIGINT", "SIGTERM", "SIGUSR1" or "signal N".
const char* signal_name(int signal);

}  // namespace afemp::core

// The public names, in namespace afemp.
namespace afemp {
using core::interrupt_signal;
using core::InterruptHandler;
using core::signal_name;
using core::take_checkpoint_request;
}  // namespace afemp
