#include "bifurcation_job.hpp"

#include <string>
#include <utility>

namespace impactlab::gui {

const char* bif_protocol_name(BifProtocol p) {
    switch (p) {
        case BifProtocol::CfUp: return "CF up";
        case BifProtocol::CfDown: return "CF down";
        case BifProtocol::Ef: return "EF ramp";
    }
    return "?";
}

BifurcationJob::~BifurcationJob() {
    cancel();
    join();
}

void BifurcationJob::join() {
    if (thread_.joinable()) thread_.join();
}

void BifurcationJob::cancel() {
    if (progress_) progress_->cancel.store(true, std::memory_order_relaxed);
}

void BifurcationJob::start(const BifRequest& req) {
    cancel();
    join();
    progress_ = std::make_unique<Progress>();
    running_.store(true, std::memory_order_release);
    Progress* prog = progress_.get();
    thread_ = std::thread([this, req, prog] {
        Diagram d;
        std::string error;
        try {
        if (req.protocol == BifProtocol::Ef) {
            EfSpec spec;
            spec.omega_max = req.omega_max;
            spec.t_ramp = req.t_ramp;
            d = run_ef_ramp(req.params, spec, prog);
        } else {
            CfSpec spec;
            spec.omega_max = req.omega_max;
            spec.omega_min = req.omega_max / req.steps;
            spec.steps = req.steps;
            spec.transient = req.transient;
            spec.record = req.record;
            spec.direction = req.protocol == BifProtocol::CfUp ? SweepDirection::Up : SweepDirection::Down;
            d = run_cf_sweep(req.params, spec, prog);
        }
        } catch (const std::exception& e) {   // a stalled run (SimulationStalled): reported, not fatal
            error = e.what();
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (error.empty()) result_ = std::move(d);
            else error_ = std::move(error);
        }
        running_.store(false, std::memory_order_release);
    });
}

std::string BifurcationJob::take_error() {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::exchange(error_, std::string());
}

std::optional<Diagram> BifurcationJob::take_result() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::optional<Diagram> out = std::move(result_);
    result_.reset();
    return out;
}

}  // namespace impactlab::gui
