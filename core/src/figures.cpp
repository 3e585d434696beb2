#include "impactlab/figures.hpp"

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <thread>
#include <vector>

namespace impactlab {

namespace {
const char* const kFig3Versions[] = {"A1C", "A1C1", "A3C", "A1G", "A1H"};
}

Figure3Data compute_figure3(int cf_steps, const Tolerances& tol, Progress* progress) {
    Figure3Data out;
    out.cf.resize(5);
    constexpr int kJobs = 6;
    Progress parts[kJobs];
    std::atomic<int> next{0};
    auto worker = [&] {
        for (int j; (j = next.fetch_add(1)) < kJobs;) {
            if (progress && progress->cancel.load()) parts[j].cancel.store(true);
            if (j == 0) {
                out.ef = run_ef_ramp(make_version("A1C"), out.ef_spec, &parts[j], tol);
            } else {
                CfSpec spec;
                spec.steps = cf_steps;
                spec.omega_min = 25.0 / cf_steps;
                out.cf[static_cast<std::size_t>(j - 1)] = run_cf_sweep(make_version(kFig3Versions[j - 1]), spec, &parts[j], tol);
            }
        }
    };
    const unsigned n_threads = std::max(1u, std::min<unsigned>(kJobs, std::thread::hardware_concurrency()));
    std::vector<std::thread> threads;
    for (unsigned i = 0; i < n_threads; ++i) threads.emplace_back(worker);
    // This thread relays progress and cancellation until the workers finish.
    std::atomic<bool> finished{false};
    std::thread relay([&] {
        while (!finished.load()) {
            double sum = 0;
            for (auto& p : parts) {
                sum += p.fraction.load();
                if (progress && progress->cancel.load()) p.cancel.store(true);
            }
            if (progress) progress->fraction.store(sum / kJobs);
            std::this_thread::sleep_for(std::chrono::milliseconds(50));
        }
    });
    for (auto& t : threads) t.join();
    finished.store(true);
    relay.join();
    if (progress) progress->fraction.store(1.0);
    return out;
}

plot::Panel diagram_panel(const Diagram& d, const std::string& title) {
    plot::Panel panel;
    panel.title = title;
    const SweepParamAxis axis = sweep_param_axis(d.over);
    panel.xlabel = std::string(sweep_param_name(d.over)) + " [" + axis.unit + "]";
    panel.ylabel = "x [mm]";
    plot::Series s;
    s.kind = plot::Series::Kind::Points;
    s.color = {20, 40, 110, 90};
    s.size = 1.0f;
    s.x.reserve(d.points.size());
    s.y.reserve(d.points.size());
    // A level with no period up to 32 within its budget is drawn apart, in grey, and named in the legend: chaos
    // or a transient longer than the budget, which a finite run cannot tell apart.
    std::vector<char> unsettled(d.points.size(), 0);
    for (const DiagramLevel& lv : d.levels)
        if (lv.period == kLevelNotSettled)
            for (std::size_t i = lv.first; i < lv.first + lv.count && i < unsettled.size(); ++i) unsettled[i] = 1;
    plot::Series grey;
    grey.kind = plot::Series::Kind::Points;
    grey.color = {150, 150, 150, 200};
    grey.size = 1.5f;
    for (std::size_t i = 0; i < d.points.size(); ++i) {
        plot::Series& to = unsettled[i] ? grey : s;
        to.x.push_back(d.points[i].omega * axis.scale);
        to.y.push_back(d.points[i].x * 1e3);
    }
    if (!grey.x.empty()) {
        s.label = "settled: periodic";
        grey.label = "not settled: no period <= 32 (chaos or a long transient)";
    }
    panel.series.push_back(std::move(s));
    if (!grey.x.empty()) panel.series.push_back(std::move(grey));
    return panel;
}

void save_diagram_png(const Diagram& d, const std::string& path) {
    plot::Figure fig;
    fig.width = 1200;
    fig.panel_height = 500;
    std::string over;
    if (d.over != SweepParam::Omega) {
        char buf[96];
        std::snprintf(buf, sizeof buf, " over %s at omega = %g rad/s", sweep_param_name(d.over), d.omega);
        over = buf;
    }
    fig.panels.push_back(diagram_panel(d, "Model " + d.model + " - " + d.protocol + " bifurcation diagram" + over +
                                              " (x at phi = 2 pi i)"));
    plot::save_png(fig, path);
}

void save_figure3_png(const Figure3Data& f, const std::string& path) {
    plot::Figure fig;
    fig.width = 1400;
    fig.panel_height = 300;
    fig.title = "Fig. 3: bifurcation diagrams, increasing omega (x sampled at phi = 2 pi i)";
    // EF forcing panel: omega(t) = 25.1 t / 2800, then the quick drop to zero.
    plot::Panel ef;
    ef.title = "EF: experimental forcing omega(t)";
    ef.xlabel = "t [s]";
    ef.ylabel = "omega [rad/s]";
    plot::Series line;
    line.kind = plot::Series::Kind::Line;
    line.size = 2.0f;
    line.color = {170, 30, 30, 255};
    const double tr = f.ef_spec.t_ramp, wm = f.ef_spec.omega_max;
    line.x = {0.0, tr, tr + 0.02 * tr, 1.1 * tr};
    line.y = {0.0, wm, 0.0, 0.0};
    ef.series.push_back(line);
    fig.panels.push_back(ef);
    const double wmax = 25.1;
    auto add = [&](const Diagram& d, const std::string& title) {
        plot::Panel p = diagram_panel(d, title);
        p.xmin = 0.0;
        p.xmax = wmax;
        p.ymin = -27.0;   // the periodic windows of A1C1 and A1G reach -25 mm
        p.ymax = 3.0;
        fig.panels.push_back(std::move(p));
    };
    add(f.ef, "Model A1C-EF");
    for (std::size_t i = 0; i < f.cf.size(); ++i) add(f.cf[i], std::string("Model ") + kFig3Versions[i] + "-CF");
    plot::save_png(fig, path);
}

}  // namespace impactlab
