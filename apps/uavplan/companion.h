// The shipped `uavplan` links neither OMPL (a baseline the benchmarks beat) nor MPI (the batch
// across machines): `uavplan bench ...` runs `uavplan-bench`, and `uavplan batch --mpi` runs
// `uavplan-mpi`, each the same command line built with what it needs, found beside this program
// and started in this process's place (exec: the same process, so mpirun's ranks and a batch's
// parent see no difference).
#pragma once

namespace uavplan::cli {

// Keeps the command line for run_companion (main calls it first).
void remember_command_line(int argc, char** argv);

// Replaces this process with `name` (beside this program) on the same command line; returns only
// when that fails, with the exit code after saying why on stderr.
int run_companion(const char* name);

}  // namespace uavplan::cli
