// The batch's MPI session in the programs that do not link MPI (companion.h): without --mpi
// there is one rank; with it, the command line goes to uavplan-mpi.
#include <cstdlib>

#include "batch_mpi.h"
#include "companion.h"

namespace uavplan::cli {

MpiSession::MpiSession(bool use) {
  if (use) std::exit(run_companion("uavplan-mpi"));
  active_ = false;  // one rank: this program holds no MPI
}

MpiSession::~MpiSession() = default;

void MpiSession::barrier() const {}

std::string MpiSession::gather(const std::string& mine) const { return mine; }

bool MpiSession::any(bool mine) const { return mine; }

}  // namespace uavplan::cli
