#include "impactlab/scan_cluster.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdlib>

namespace impactlab {

namespace {

// A worker's first message asks for a row; each row handed out is an int (-1: none left); each result a
// ScanRowMessage.
constexpr int kTagRequest = 1, kTagRow = 2, kTagResult = 3;

bool launched_by_mpirun() {
    return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_SIZE");
}

}  // namespace

ScanCluster::ScanCluster() {
    if (!launched_by_mpirun()) return;
    MPI_Init(nullptr, nullptr);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
    active_ = true;
}

ScanCluster::~ScanCluster() {
    if (active_) MPI_Finalize();
}

bool ScanCluster::agree(bool ok) const {
    if (!active_) return ok;
    int said = ok ? 1 : 0;
    MPI_Bcast(&said, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return said != 0;
}

void ScanCluster::hand_out(const ScanSpec& spec, const std::vector<int>& todo, Progress* progress,
                           const std::function<void(int, const std::vector<ScanPoint>&)>& on_row) const {
    const std::size_t nx = static_cast<std::size_t>(spec.x.n);
    std::size_t next = 0, finished = 0;
    int stopped = 0;
    std::vector<double> buf(ScanRowMessage::size(nx));
    while (stopped < ranks_ - 1) {
        MPI_Status st;
        MPI_Recv(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &st);
        if (st.MPI_TAG == kTagResult) {
            const ScanRowMessage m = ScanRowMessage::unpack(buf, nx);
            on_row(m.row, m.points);
            if (progress) progress->fraction.store(static_cast<double>(++finished) / std::max<std::size_t>(1, todo.size()));
        }
        int row = -1;
        if (next < todo.size()) row = todo[next++];
        else ++stopped;
        MPI_Send(&row, 1, MPI_INT, st.MPI_SOURCE, kTagRow, MPI_COMM_WORLD);
    }
}

void ScanCluster::work(const Params& p, const ScanSpec& spec, const Tolerances& tol) const {
    double request = 0;
    MPI_Send(&request, 1, MPI_DOUBLE, 0, kTagRequest, MPI_COMM_WORLD);
    for (;;) {
        int row = -1;
        MPI_Recv(&row, 1, MPI_INT, 0, kTagRow, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        if (row < 0) return;
        const std::vector<double> buf = ScanRowMessage{row, scan_row(p, spec, row, tol)}.pack();
        MPI_Send(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, 0, kTagResult, MPI_COMM_WORLD);
    }
}

}  // namespace impactlab
