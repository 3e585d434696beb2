// impactlab basins: basins of attraction at constant omega, with their attractors.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <numbers>
#include <tuple>
#include <utility>

#include "analysis_common.hpp"
#include "commands.hpp"
#include "impactlab/input_file.hpp"
#include "impactlab/plot.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::cli {

namespace {

// The basin flags: omega, the grid of starts and its window, the budgets, the threads, the integrator.
analysis::BasinSpec basin_spec(const Args& a, const Params& p) {
    if (!a.has("--omega")) throw UsageError("basins: missing required option '--omega'");
    analysis::BasinSpec spec;
    spec.omega = a.num("--omega", 0, 1e-2, 1000.0);
    spec.nx = spec.nv = a.integer("--grid", 200, 1, 4000);
    analysis::set_default_window(p, spec);
    std::tie(spec.x_min, spec.x_max) = a.range("--x-range", -0.1, 0.1, {spec.x_min, spec.x_max});   // the rail
    std::tie(spec.v_min, spec.v_max) = a.range("--v-range", -100.0, 100.0, {spec.v_min, spec.v_max});
    check_start(p, spec.x_max, "basins", "--x-range (its upper end)");
    spec.transient = a.integer("--transient", spec.transient, 0, 1000000);
    spec.periods = a.integer("--periods", spec.periods, 1, 1000000);
    spec.max_period = a.integer("--max-period", spec.max_period, 1, 256);
    spec.threads = a.integer("--threads", 0, 0, 1024);
    if (a.has("--rtol")) spec.sim = tolerances_from(a);
    return spec;
}

// One x0,v0,label row per cell, v0 slowest.
void write_labels(OutputFile& out, const analysis::BasinSpec& spec, const analysis::BasinResult& r) {
    out << "x0,v0,label\n";
    for (int j = 0; j < spec.nv; ++j)
        for (int i = 0; i < spec.nx; ++i)
            out << r.x0(i) << ',' << r.v0(j) << ',' << r.label[static_cast<std::size_t>(j) * spec.nx + i] << '\n';
    out.check();
}

// An attractor in the legend's words: its kind and its well.
std::string describe(const analysis::Attractor& at) {
    std::string kind = at.kind == analysis::AttractorKind::Periodic ? "period " + std::to_string(at.period)
                       : at.kind == analysis::AttractorKind::Resting ? "resting at the bumper"
                                                                     : std::string(analysis::attractor_kind_name(at.kind));
    const char* well = at.well < 0 ? "left well" : at.well > 0 ? "right well" : "at x = 0";
    return kind + ", " + well;
}

// The legend: one line per label.
void print_legend(const analysis::BasinResult& r, std::size_t ncells) {
    std::printf("label,kind,period,well,x,v,cells,fraction\n");
    for (const auto& at : r.attractors)
        std::printf("%d,%s,%d,%s,%.6g,%.6g,%zu,%.4f\n", at.id, analysis::attractor_kind_name(at.kind), at.period,
                    at.well < 0 ? "left" : at.well > 0 ? "right" : "hilltop", at.representative[0], at.representative[1],
                    at.cells, static_cast<double>(at.cells) / static_cast<double>(ncells));
}

// The map: one series per attractor holding its cells' centres (its legend entry says what it is), and
// the attractors' section points over them.
plot::Figure basin_figure(const Params& p, const analysis::BasinSpec& spec, const analysis::BasinResult& r) {
    plot::Figure fig;
    fig.width = 1000;
    fig.panel_height = 800;
    char omega_txt[32];
    std::snprintf(omega_txt, sizeof omega_txt, "%g", spec.omega);
    fig.title = p.name + ": basins of attraction at omega = " + omega_txt + " rad/s (starts at phi = 0)";
    plot::Panel pan;
    pan.xlabel = "x0 [m]";
    pan.ylabel = "v0 [m/s]";
    pan.xmin = spec.x_min;
    pan.xmax = spec.x_max;
    pan.ymin = spec.v_min;
    pan.ymax = spec.v_max;
    pan.grid = false;
    const plot::Color palette[] = {{31, 119, 180, 255}, {255, 127, 14, 255}, {44, 160, 44, 255}, {214, 39, 40, 255},
                                   {148, 103, 189, 255}, {140, 86, 75, 255}, {227, 119, 194, 255}, {188, 189, 34, 255},
                                   {23, 190, 207, 255}, {127, 127, 127, 255}};
    std::vector<plot::Series> fills(r.attractors.size());
    for (std::size_t k = 0; k < r.attractors.size(); ++k) {
        const auto& at = r.attractors[k];
        fills[k].kind = plot::Series::Kind::Points;
        fills[k].color = palette[k % std::size(palette)];
        if (at.kind == analysis::AttractorKind::Chaos) fills[k].color = {190, 190, 190, 255};
        char rep[96];
        std::snprintf(rep, sizeof rep, " (%.2f mm, %.3f m/s)", at.representative[0] * 1e3, at.representative[1]);
        fills[k].label = std::to_string(at.id) + ": " + describe(at) + rep;
    }
    for (int j = 0; j < spec.nv; ++j)
        for (int i = 0; i < spec.nx; ++i) {
            const int id = r.label[static_cast<std::size_t>(j) * spec.nx + i];
            if (id < 0) continue;
            fills[static_cast<std::size_t>(id)].x.push_back(r.x0(i));
            fills[static_cast<std::size_t>(id)].y.push_back(r.v0(j));
        }
    plot::Series att{plot::Series::Kind::Points, {}, {}, {0, 0, 0, 255}, 2.5f, "section points of the attractors"};
    for (const auto& at : r.attractors)
        for (const auto& q : at.points) {
            att.x.push_back(q[0]);
            att.y.push_back(q[1]);
        }
    pan.series = fills;
    pan.series.push_back(att);
    fig.panels.push_back(pan);
    return fig;
}

// Each cell painted as sub x sub dots, each just covering its sub-rectangle (corner to corner): the
// overlap into a neighbour stays below a pixel, so the basin boundaries are the grid's.
void spread_cells(plot::Figure& fig, const analysis::BasinSpec& spec, std::size_t nfills) {
    const plot::Mapping m = plot::layout(fig)[0];
    const double cw = static_cast<double>(m.right - m.left) / spec.nx, ch = static_cast<double>(m.bottom - m.top) / spec.nv;
    const int sub = std::max(1, static_cast<int>(std::ceil(std::max(cw, ch) / 1.5)));
    const double dx = (spec.x_max - spec.x_min) / spec.nx, dv = (spec.v_max - spec.v_min) / spec.nv;
    for (std::size_t k = 0; k < nfills; ++k) {
        plot::Series& f = fig.panels[0].series[k];
        f.size = static_cast<float>(0.5 * std::hypot(cw, ch) / sub + 0.25);
        std::vector<double> fx, fy;
        fx.reserve(f.x.size() * static_cast<std::size_t>(sub * sub));
        fy.reserve(fx.capacity());
        for (std::size_t c = 0; c < f.x.size(); ++c)
            for (int sa = 0; sa < sub; ++sa)
                for (int sb = 0; sb < sub; ++sb) {
                    fx.push_back(f.x[c] + ((sa + 0.5) / sub - 0.5) * dx);
                    fy.push_back(f.y[c] + ((sb + 0.5) / sub - 0.5) * dv);
                }
        f.x = std::move(fx);
        f.y = std::move(fy);
    }
}

}  // namespace

int cmd_basins(const std::vector<std::string>& argv) {
    if (wants_help(argv, "usage: impactlab basins --model A1G --omega 13 --grid 200 --out basins.csv [--png basins.png]\n\n"
                         "Basins of attraction at constant omega: a grid of starts (x0, v0) at phi = 0 (cell centres), each\n"
                         "simulated until its Poincare section points recur (period k) or its budget ends (chaos), and\n"
                         "labelled by its attractor (the same orbit from different cells gets the same label). Writes\n"
                         "x0,v0,label rows; prints the legend: label, kind (period k, chaos, resting at the bumper), well,\n"
                         "a section point of the attractor, the cells reaching it.\n"
                         "  --omega W        forcing frequency [rad/s] (required)\n"
                         "  --grid N         N x N starts (default 200)\n"
                         "  --x-range A:B    x0 range [m] (default -0.03:xI, or -0.03:0.03 without a bumper)\n"
                         "  --v-range A:B    v0 range [m/s] (default -0.3:0.3)\n"
                         "  --transient N    periods a cell may take to settle (default 60)\n"
                         "  --periods N      further periods before a cell counts as chaotic; its last N section points\n"
                         "                   are its attractor (default 40)\n"
                         "  --max-period K   the longest period recognised (default 16)\n"
                         "  --threads N      worker threads (default: all cores); the labels do not depend on it\n"
                         "  (--rtol: the integrator's tolerance, default 1e-6 here: the attractor, not its digits)\n"
                         "  --out FILE       CSV output x0,v0,label (required)\n"
                         "  --png FILE       the coloured basin map with the attractors' section points and a legend\n"))
        return 0;
    const Args a("basins", argv,
                 with_model_flags({"--omega", "--grid", "--x-range", "--v-range", "--transient", "--periods", "--max-period",
                                   "--threads", "--out", "--png"}));
    const Params p = model_from(a, "A1G");
    const analysis::BasinSpec spec = basin_spec(a, p);
    const std::string out_path = a.required("--out");
    const std::string png = a.str("--png", "");
    if (a.has("--png")) check_writable(png, "--png");
    auto out = open_out(out_path);
    Progress progress;
    analysis::BasinResult r;
    {
        ProgressBar bar("basins " + p.name, progress);
        r = analysis::compute_basins(p, spec, &progress);
    }
    write_labels(out, spec, r);
    const std::size_t ncells = r.label.size();
    std::fprintf(stderr, "%s omega = %g rad/s: %d x %d starts, %zu attractors, %.3g periods per start, %.2f s on %d threads -> %s\n",
                 printable(p.name).c_str(), spec.omega, spec.nx, spec.nv, r.attractors.size(),
                 static_cast<double>(r.periods_run) / static_cast<double>(ncells), r.seconds, r.threads, printable(out_path).c_str());
    print_legend(r, ncells);
    if (r.cancelled) {
        std::fprintf(stderr, "basins: cancelled\n");
        return 1;
    }
    if (a.has("--png")) {
        plot::Figure fig = basin_figure(p, spec, r);
        spread_cells(fig, spec, r.attractors.size());
        plot::save_png(fig, png);
        std::fprintf(stderr, "plot -> %s\n", printable(png).c_str());
    }
    return 0;
}

}  // namespace impactlab::cli
