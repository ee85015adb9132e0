// Crash tests' hook (tests/core/test_restart.cpp): with AFEMP_FAULT="NAME:N" in the environment,
// the Nth pass through fault_point(NAME) kills the process with SIGKILL on the spot, nothing
// flushed or closed, as a power cut or the kernel's OOM killer would. Without it (every user's
// run) a point costs one comparison. Points: "frame" (inside a field frame's write, its data
// written but not flushed), "checkpoint" (inside a checkpoint's write, the model's state
// written but not the rest) and "step" (after each step of the time loop). "NAME:N@R" kills
// only the process of MPI rank R (OMPI_COMM_WORLD_RANK or PMI_RANK): a rank of a divided run
// that dies (tests/mpm/test_cli.cpp).
#pragma once

namespace afemp::core {

void fault_point(const char* name);

}  // namespace afemp::core
