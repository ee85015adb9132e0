// Stopping a run cleanly on SIGINT (Ctrl-C) or SIGTERM. The `afemp run` command installs the
// handler for the run's length: the first signal asks the time loop to stop after the step it
// is in (a checkpoint, the final history row, frame and summary are written); it also restores
// the default action, so a second signal ends the process at once. SIGUSR1 asks for a
// checkpoint after the step and the run goes on. The library installs nothing itself.
#pragma once

namespace afemp::core {

class InterruptHandler {
 public:
  InterruptHandler();   // installs the handler for SIGINT, SIGTERM and SIGUSR1
  ~InterruptHandler();  // restores what was there before
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;
};

// The signal that asked the run to stop (SIGINT or SIGTERM), or 0.
int interrupt_signal();
// Whether SIGUSR1 came since the last call (the request is then cleared).
bool take_checkpoint_request();
// "SIGINT", "SIGTERM", "SIGUSR1" or "signal N".
const char* signal_name(int signal);

}  // namespace afemp::core
