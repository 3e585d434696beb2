// A bifurcation diagram computed on a worker thread (the core's run_cf_sweep / run_ef_ramp) with progress
// and cancel through impactlab::Progress; the finished Diagram is handed to the UI whole. GL-free.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "impactlab/params.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab::gui {

enum class BifProtocol { CfUp, CfDown, Ef };
const char* bif_protocol_name(BifProtocol p);

struct BifRequest {
    Params params;
    BifProtocol protocol = BifProtocol::CfUp;
    int steps = 300;           // CF: number of omega values
    int transient = 20;        // CF: periods discarded at each omega
    int record = 70;           // CF: periods recorded
    double omega_max = 25.0;   // CF: last omega; EF: omega reached at the end of the ramp
    double t_ramp = 2800.0;    // EF [s]
};

class BifurcationJob {
public:
    BifurcationJob() = default;
    ~BifurcationJob();   // cancels and joins
    BifurcationJob(const BifurcationJob&) = delete;
    BifurcationJob& operator=(const BifurcationJob&) = delete;

    // UI thread. Cancels any job in progress and starts a new one.
    void start(const BifRequest& req);
    // UI thread. Asks the job to stop; its partial result arrives marked cancelled.
    void cancel();
    // Any thread.
    bool running() const { return running_.load(std::memory_order_acquire); }
    double progress() const { return progress_ ? progress_->fraction.load(std::memory_order_relaxed) : 0.0; }
    // UI thread. The finished diagram, once (then empty until the next job finishes).
    std::optional<Diagram> take_result();
    // UI thread. Why the last job failed, once ("" if it did not).
    std::string take_error();

private:
    void join();
    std::unique_ptr<Progress> progress_;
    std::thread thread_;
    std::atomic<bool> running_{false};
    std::mutex mutex_;                 // guards result_ (handed over whole, once)
    std::optional<Diagram> result_;
    std::string error_;
};

}  // namespace impactlab::gui
