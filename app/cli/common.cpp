#include "common.hpp"

#include <sstream>

#include <cstdio>
#include <unistd.h>

#include "impactlab/params_json.hpp"

namespace impactlab::cli {

Params model_from(const Args& a, const std::string& fallback) {
    Params p;
    const std::string name = a.str("--model", fallback);
    try {
        p = resolve_model(name);
    } catch (const ParamError& e) {
        throw UsageError(std::string("--model: ") + e.what());
    }
    if (a.has("--xI")) {
        p.xI = a.num("--xI", 0.0, -0.05, 0.05);
        p.name += "(xI=" + a.str("--xI", "") + ")";
    }
    if (a.has("--m0e")) p.m0e = a.num("--m0e", p.m0e, 0.0, 10.0);
    validate(p, name);
    return p;
}

Tolerances tolerances_from(const Args& a) {
    Tolerances t;
    t.rtol = a.num("--rtol", t.rtol, 1e-13, 1e-2);
    return t;
}

std::set<std::string> with_model_flags(std::set<std::string> flags) {
    flags.insert(kModelFlags.begin(), kModelFlags.end());
    return flags;
}

std::ofstream open_out(const std::string& path) {
    std::ofstream out(path);
    if (!out) throw UsageError(path + ": cannot open for writing");
    out.precision(10);
    return out;
}

std::vector<std::string> split_list(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

std::optional<identify::MeasuredData> input_from(const Args& a, const std::string& command) {
    const bool input = a.has("--input");
    for (const auto& f : kInputFlags)
        if (f != "--input" && a.has(f) && !input) throw UsageError(command + ": " + f + " needs --input");
    if (!input) return std::nullopt;
    identify::LoadOptions lo;
    lo.columns.u = a.str("--u-col", "");
    lo.columns.x = a.str("--x-col", "");
    lo.columns.t = a.str("--t-col", "");
    lo.rate = a.num("--input-rate", 0.0, 1e-6, 1e9);
    lo.u_scale = a.num("--u-scale", 1.0, -1e12, 1e12);
    lo.min_samples = 2;   // an input needs two samples to be a signal
    identify::MeasuredData in;
    try {
        in = identify::load_measured(a.str("--input", ""), lo);
    } catch (const identify::DataError& e) {
        throw UsageError(command + ": --input: " + e.what());
    }
    if (!in.has_u()) throw UsageError(command + ": --input: " + in.source + " has no input column u (map one with --u-col)");
    return in;
}

ProgressBar::ProgressBar(const std::string& label, Progress& progress) : ProgressBar(label, progress.fraction) {}

ProgressBar::ProgressBar(const std::string& label, const std::atomic<double>& fraction, std::function<std::string()> stage)
    : label_(label), fraction_(fraction), stage_(std::move(stage)) {
    // On a terminal the bar redraws in place; into a log file it writes a line per 10 %.
    const bool tty = isatty(fileno(stderr)) != 0;
    thread_ = std::thread([this, tty] {
        const auto start = std::chrono::steady_clock::now();
        int last_decile = -1;
        while (!done_.load()) {
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
            const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            if (elapsed < 1.0 || done_.load()) continue;
            const double f = std::clamp(fraction_.load(), 0.0, 1.0);
            const std::string now = stage_ ? stage_() : std::string();
            if (!tty) {
                const int decile = static_cast<int>(f * 10);
                if (decile != last_decile)
                    std::fprintf(stderr, "%s: %3d%%  %5.0f s%s%s\n", label_.c_str(), decile * 10, elapsed, now.empty() ? "" : "  ", now.c_str());
                last_decile = decile;
                continue;
            }
            const int width = 30, filled = static_cast<int>(f * width);
            std::fprintf(stderr, "\r%-28s [%s%s] %5.1f%%  %5.0f s  %-34.34s", label_.c_str(), std::string(filled, '#').c_str(),
                         std::string(width - filled, '.').c_str(), 100 * f, elapsed, now.c_str());
            std::fflush(stderr);
            drawn_ = true;
        }
    });
}

void ProgressBar::finish() {
    if (done_.exchange(true)) return;
    thread_.join();
    if (drawn_) std::fprintf(stderr, "\r%-28s done%86s\n", label_.c_str(), "");
    else if (!isatty(fileno(stderr))) std::fflush(stderr);
}

ProgressBar::~ProgressBar() { finish(); }

}  // namespace impactlab::cli
