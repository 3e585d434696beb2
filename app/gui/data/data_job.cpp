#include "data_job.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <exception>
#include <string>
#include <stdexcept>
#include <utility>

namespace impactlab::gui {

namespace {
double clock_s() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

std::string panel_wording(const std::string& msg) {
    // Longest flags first, so "--x-scale" is not read as "--x" ... ; each maps to the field that does its job.
    static const std::pair<const char*, const char*> kFields[] = {
        {"--baseline fit --fit-params xI", "the x_I slider (the panel fits with x_I fixed)"},
        {"--phi-col or --u-col", "the forcing column and \"forcing is an input u\" (Column mapping)"},
        {"--x-scale", "\"x scale\" (Column mapping)"},
        {"--x-col", "the x column (Column mapping)"},
        {"--t-col", "the time column (Column mapping)"},
        {"--phi-col", "the forcing column (Column mapping)"},
        {"--u-col", "\"forcing is an input u\" (Column mapping)"},
        {"--rate HZ", "a sample rate (Column mapping)"},
        {"--rate", "the sample rate (Column mapping)"},
        {"--xI", "the x_I slider"},
        {"--free", "\"a free run\" (Column mapping)"},
    };
    std::string out;
    std::size_t i = 0;
    while (i < msg.size()) {
        if (msg.compare(i, 2, "--") == 0) {
            bool mapped = false;
            for (const auto& [flag, field] : kFields) {
                const std::size_t n = std::char_traits<char>::length(flag);
                if (msg.compare(i, n, flag) == 0) {
                    out += field;
                    i += n;
                    mapped = true;
                    break;
                }
            }
            if (mapped) continue;
            // A flag the panel has no field for: say where it lives.
            std::size_t j = i + 2;
            while (j < msg.size() && (std::isalnum(static_cast<unsigned char>(msg[j])) || msg[j] == '-')) ++j;
            out += (j > i + 2 ? "the command line's " : "") + msg.substr(i, j - i);   // a bare "--" stays
            i = j;
            continue;
        }
        out += msg[i++];
    }
    return out;
}

identify::LoadOptions load_options_from(const DataColumns& c) {
    identify::LoadOptions o;
    o.columns.t = c.t;
    o.columns.x = c.x;
    if (c.forcing_is_u) {
        o.columns.u = c.forcing.empty() ? "u" : c.forcing;
        // The loader looks for phi by its conventional name; a u-forced file must not pick one up.
        o.columns.phi = "";
    } else {
        o.columns.phi = c.forcing;
    }
    o.rate = c.rate;
    o.x_scale = c.x_scale;
    o.free_run = c.free_run;
    return o;
}

std::uint32_t all_effects_mask(const identify::FitReport& report) {
    const std::size_t n = std::min(report.effects_found.size(), kMaxToggleEffects);
    return n >= 32 ? 0xFFFFFFFFu : ((std::uint32_t{1} << n) - 1u);
}

identify::Model model_for_subset(const identify::FitReport& report, std::uint32_t mask) {
    identify::Model m = report.before;
    const std::size_t n = std::min(report.effects_found.size(), kMaxToggleEffects);
    for (std::size_t k = 0; k < n; ++k)
        if (mask & (std::uint32_t{1} << k)) {
            const identify::FoundEffect& f = report.effects_found[k];
            identify::apply_effect(m, f.id, f.parameters);
            m.p.name += "+" + f.id;
        }
    return m;
}

identify::Model model_for_data(const std::string& name, const identify::MeasuredData& data) {
    return identify::resolve_fit_model(name, identify::forcing_of(data));
}

std::pair<double, double> robust_extent(const std::vector<const std::vector<double>*>& series, double q, double pad) {
    std::vector<double> all;
    for (const auto* s : series)
        for (double v : *s)
            if (std::isfinite(v)) all.push_back(v);
    if (all.empty()) return {0.0, 0.0};
    const auto n = all.size();
    const auto k_lo = static_cast<std::size_t>(q * static_cast<double>(n - 1));
    const auto k_hi = n - 1 - k_lo;
    std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(k_lo), all.end());
    const double lo = all[k_lo];
    std::nth_element(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(k_hi), all.end());
    const double hi = all[k_hi];
    const double span = hi - lo;
    return {lo - pad * span, hi + pad * span};
}

DataJob::~DataJob() {
    cancel();
    reap(true);
}

void DataJob::reap(bool all) {
    for (auto it = workers_.begin(); it != workers_.end();) {
        if (all || it->done->load(std::memory_order_acquire)) {
            if (it->thread.joinable()) it->thread.join();
            it = workers_.erase(it);
        } else {
            ++it;
        }
    }
}

void DataJob::cancel() {
    if (fit_progress_) fit_progress_->cancel.store(true, std::memory_order_relaxed);
    std::lock_guard<std::mutex> lock(mutex_);
    wanted_.store(0, std::memory_order_release);
    busy_.store(false, std::memory_order_release);
    result_.reset();
}

double DataJob::running_for_s() const { return running() ? clock_s() - started_s_ : 0.0; }

std::uint64_t DataJob::launch(DataJobResult::Kind kind, std::function<void(DataJobResult&)> work) {
    reap(false);
    const std::uint64_t id = ++next_id_;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        wanted_.store(id, std::memory_order_release);
        busy_.store(true, std::memory_order_release);
        result_.reset();
    }
    kind_ = kind;
    started_s_ = clock_s();
    auto done = std::make_shared<std::atomic<bool>>(false);
    auto body = [this, id, kind, done, work = std::move(work)] {
        DataJobResult r;
        r.kind = kind;
        r.id = id;
        try {
            work(r);
        } catch (const std::exception& e) {
            r.error = e.what();
        } catch (...) {
            r.error = "unknown error";
        }
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (wanted_.load(std::memory_order_acquire) == id) {
                result_ = std::move(r);
                busy_.store(false, std::memory_order_release);
            }
        }
        done->store(true, std::memory_order_release);
    };
#ifdef __EMSCRIPTEN__
    body();   // a browser page has no threads: the job runs here, whole
#else
    workers_.push_back({std::thread(std::move(body)), std::move(done)});
#endif
    return id;
}

std::uint64_t DataJob::start_load(const std::string& path, const identify::LoadOptions& options) {
    return launch(DataJobResult::Kind::Load, [path, options](DataJobResult& r) {
        r.data = std::make_shared<const identify::MeasuredData>(identify::load_measured(path, options));
    });
}

std::uint64_t DataJob::start_fit(std::shared_ptr<const identify::MeasuredData> data, const identify::Model& model,
                                 const identify::FitOptions& options) {
    if (fit_progress_) fit_progress_->cancel.store(true, std::memory_order_relaxed);   // a superseded fit stops
    auto progress = std::make_shared<identify::FitProgress>();
    const std::uint64_t id = launch(DataJobResult::Kind::Fit, [data, model, options, progress](DataJobResult& r) {
#ifdef __EMSCRIPTEN__
        // The page has no least squares (Ceres); leaving the fit's code out keeps the page small.
        (void)r;
        throw std::runtime_error("the fit runs in the desktop program (impactlab fit, or impactlab-gui), not in a browser");
#else
        r.report = std::make_shared<const identify::FitReport>(identify::run_fit(*data, model, options, nullptr, progress.get()));
#endif
    });
    fit_progress_ = std::move(progress);
    return id;
}

std::uint64_t DataJob::start_evaluate(std::shared_ptr<const identify::MeasuredData> data, const identify::Model& model,
                                      const identify::FitOptions& options, std::uint32_t mask) {
    return launch(DataJobResult::Kind::Evaluate, [data, model, options, mask](DataJobResult& r) {
        r.mask = mask;
#ifdef __EMSCRIPTEN__
        throw std::runtime_error("the model's errors are computed in the desktop program, not in a browser");
#else
        r.errors = identify::evaluate_model(*data, model, options);
#endif
    });
}

std::optional<DataJobResult> DataJob::take_result() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::optional<DataJobResult> out = std::move(result_);
    result_.reset();
    return out;
}

bool DataJob::wait(double timeout_s) {
    const double until = clock_s() + timeout_s;
    while (running()) {
        if (clock_s() > until) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return true;
}

}  // namespace impactlab::gui
