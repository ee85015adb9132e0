// Stopping a run cleanly on SIGINT (Ctrl-C) or SIGTERM. The `afemp run` command installs the
// handler for the run's length: the first signal asks the time loop to stop after the step it
// is in (the final history row, frame and summary are written); it also restores the default
// action, so a second signal ends the process at once. The library installs nothing itself.
#pragma once

namespace afemp::core {

class InterruptHandler {
 public:
  InterruptHandler();   // installs the handler for SIGINT and SIGTERM
  ~InterruptHandler();  // restores what was there before
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;
};

// The signal that asked the run to stop (SIGINT or SIGTERM), or 0.
int interrupt_signal();
// "SIGINT", "SIGTERM" or "signal N".
const char* signal_name(int signal);

}  // namespace afemp::core
