// A parameter plane across processes and machines (Open MPI): rank 0 hands rows out one at a time to
// whichever rank asks and records each finished row as it comes back; the other ranks compute. Rows are
// independent (scan.hpp), so the plane is the same bit for bit whatever the number of ranks. Built only where
// MPI is found, as the library impactlab_scan_cluster (it defines IMPACTLAB_HAVE_MPI for those that link it),
// so the core and the programs that never scan across machines stay free of MPI.
#pragma once

#include <functional>
#include <vector>

#include "impactlab/scan.hpp"

namespace impactlab {

class ScanCluster {
public:
    // MPI is started only when mpirun launched the process (Open MPI sets its environment): a plain run is
    // one rank and needs no daemon.
    ScanCluster();
    ~ScanCluster();
    ScanCluster(const ScanCluster&) = delete;
    ScanCluster& operator=(const ScanCluster&) = delete;

    int rank() const { return rank_; }
    int ranks() const { return ranks_; }
    // Rank 0 tells the others whether its setup went well: every rank returns rank 0's ok (one rank: its own).
    // A collective call: every rank makes it once.
    bool agree(bool ok) const;
    // Rank 0: hands `todo` out row by row as the other ranks ask and calls on_row for each row they send
    // back, one call at a time on this thread. Progress counts the rows of todo.
    void hand_out(const ScanSpec& spec, const std::vector<int>& todo, Progress* progress,
                  const std::function<void(int row, const std::vector<ScanPoint>&)>& on_row) const;
    // Any other rank: computes the rows rank 0 hands out until it has none left.
    void work(const Params& p, const ScanSpec& spec, const Tolerances& tol) const;

private:
    int rank_ = 0, ranks_ = 1;
    bool active_ = false;   // MPI_Init was called
};

}  // namespace impactlab
