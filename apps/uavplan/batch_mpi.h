// The batch across machines: Open MPI's ranks split the runs, rank 0 gathers the results.
// Only `uavplan batch --mpi` starts MPI; every other command runs without it.
#pragma once

#include <string>

namespace uavplan::cli {

class MpiSession {
 public:
  explicit MpiSession(bool use);  // MPI_Init (funneled: only the main thread calls MPI)
  ~MpiSession();                  // MPI_Finalize
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  void barrier() const;
  // Rank 0 receives every rank's text, in rank order; the others receive "".
  std::string gather(const std::string& mine) const;
  // Whether any rank says true.
  bool any(bool mine) const;

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
};

}  // namespace uavplan::cli
