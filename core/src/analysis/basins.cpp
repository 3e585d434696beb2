// Basins of attraction: a grid of starts (x0, v0) at phi = 0, each run through the Simulator until its
// Poincare section points recur (period k), or its budget ends (chaos); the outcomes matched into attractors
// after all cells are done, in cell order, so that the labels never depend on the thread count.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <numbers>
#include <stdexcept>
#include <thread>
#include <unordered_map>
#include <cstdint>

#include "impactlab/analysis.hpp"

namespace impactlab::analysis {

namespace {

// Notes whether the cart flew at all during a period: held through whole periods is "resting", not a
// periodic orbit that happens to be at the bumper at each section.
class FreeWatch : public Observer {
public:
    bool flew = false;
    void on_piece(const Piece& piece) override {
        if (piece.regime == Regime::Free && piece.t1 > piece.t0) flew = true;
    }
};

// The smallest k <= max_period for which the last max(confirm k, min_points) points each lie within tol of
// the point k periods earlier; 0 if none. y[0] is the start, y[n-1] the newest section point.
int recurrence(const std::vector<Vec2>& y, std::size_t n, int max_period, int confirm, int min_points, double tol) {
    for (int k = 1; k <= max_period; ++k) {
        const std::size_t need = static_cast<std::size_t>(std::max(confirm * k, min_points));
        if (n < need + static_cast<std::size_t>(k)) break;
        bool ok = true;
        for (std::size_t j = n - 1; j + need >= n && ok; --j) ok = scaled_norm(y[j] - y[j - static_cast<std::size_t>(k)]) < tol;
        if (ok) return k;
    }
    return 0;
}

// Distance of point q to the nearest point of set B (scaled).
double nearest(const Vec2& q, const std::vector<Vec2>& B) {
    double d = 1e300;
    for (const auto& b : B) d = std::min(d, scaled_norm(q - b));
    return d;
}

// Median over A of the nearest-neighbour distance to B.
double median_nearest(const std::vector<Vec2>& A, const std::vector<Vec2>& B) {
    std::vector<double> d;
    d.reserve(A.size());
    for (const auto& a : A) d.push_back(nearest(a, B));
    std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
    return d[d.size() / 2];
}

// A cycle whose stability has been computed, kept per worker thread: the decision is a property of the orbit,
// so a cache hit and a recomputation agree and the labels stay independent of the thread count.
struct CheckedCycle { int period; std::vector<Vec2> points; bool stable; };

// Whether the recurring cycle (the last k points, ending at y_end) is a stable orbit. An unstable one can
// recur for dozens of periods: a permanent contact (regime III) forgets the state, so a chaotic trajectory
// may land on a saddle cycle to round-off (A1G, omega 13: a period-6 orbit with mu = -1.74) and needs
// ln(1e-5 / 1e-16) / ln 1.74 ~ 45 periods to leave it.
bool cycle_stable(const Params& p, const BasinSpec& spec, const std::vector<Vec2>& y, std::size_t n, int k,
                  std::vector<CheckedCycle>& cache) {
    const auto first = y.begin() + static_cast<std::ptrdiff_t>(n) - k, last = y.begin() + static_cast<std::ptrdiff_t>(n);
    for (const auto& c : cache) {
        if (c.period != k) continue;
        bool same = true;
        for (auto it = first; it != last && same; ++it) {
            double d = 1e300;
            for (const auto& q : c.points) d = std::min(d, scaled_norm(*it - q));
            same = d < spec.match_tol;
        }
        if (same) return c.stable;
    }
    // The monodromy of the k-th map (tangent with saltation) at the analysis tolerance.
    bool stable = false;   // a stalled check counts as unstable: the cell then runs its whole budget
    try {
        stable = floquet(poincare_map(p, spec.omega, y[n - 1], k, true, analysis_tolerances()).M).stable;
    } catch (const SimulationStalled&) {
    }
    cache.push_back({k, std::vector<Vec2>(first, last), stable});
    return stable;
}

void validate(const BasinSpec& s) {
    if (s.nx < 1 || s.nv < 1) throw std::invalid_argument("basins: the grid needs at least 1 x 1 cells");
    if (!(s.x_max > s.x_min) || !(s.v_max > s.v_min)) throw std::invalid_argument("basins: an empty or inverted range");
    if (!(s.omega > 0) || !std::isfinite(s.omega)) throw std::invalid_argument("basins: omega must be positive");
    if (s.periods < 1 || s.transient < 0 || s.max_period < 1 || s.confirm < 1)
        throw std::invalid_argument("basins: periods, max_period and confirm must be at least 1");
}

}  // namespace

const char* attractor_kind_name(AttractorKind k) {
    switch (k) {
        case AttractorKind::Periodic: return "period";
        case AttractorKind::Chaos: return "chaos";
        case AttractorKind::Resting: return "resting";
        case AttractorKind::Failed: return "failed";
    }
    return "?";
}

namespace {

// The coarse cells' section points, found again in O(1): a later cell whose trajectory follows one of them for
// two consecutive periods (within kShadowTol) ends where that one ended. The table is complete before any
// cell consults it, so every cell's outcome is a function of its start alone, whatever the thread count.
constexpr double kShadowTol = 1e-3;   // scaled (x / 1 cm, v / 0.1 m/s)
constexpr int kCoarseStride = 4;      // every 4th cell in x and in v runs first, without the table

struct ShadowTable {
    struct Entry { std::uint32_t cell, index; };
    std::unordered_map<std::uint64_t, std::vector<Entry>> buckets;
    const std::vector<std::vector<Vec2>>* traces = nullptr;   // per cell (empty for cells not in the table)
    const std::vector<CellOutcome>* outcomes = nullptr;

    static std::int64_t coord(double scaled) { return static_cast<std::int64_t>(std::floor(scaled / kShadowTol)); }
    static std::uint64_t key(std::int64_t i, std::int64_t j) {
        return (static_cast<std::uint64_t>(i) << 32) ^ (static_cast<std::uint64_t>(j) & 0xffffffffULL);
    }
    void insert(std::uint32_t cell, std::uint32_t index, const Vec2& y) {
        buckets[key(coord(y[0] / kXScale), coord(y[1] / kVScale))].push_back({cell, index});
    }
    // The outcome of a coarse trajectory that passes within kShadowTol of `prev` and then of `now` one period
    // later, if any (the first in cell order, so that the choice is deterministic too).
    const CellOutcome* follow(const Vec2& prev, const Vec2& now) const {
        const std::int64_t ci = coord(prev[0] / kXScale), cj = coord(prev[1] / kVScale);
        const Entry* best = nullptr;
        for (std::int64_t di = -1; di <= 1; ++di)
            for (std::int64_t dj = -1; dj <= 1; ++dj) {
                const auto it = buckets.find(key(ci + di, cj + dj));
                if (it == buckets.end()) continue;
                for (const Entry& e : it->second) {
                    const auto& tr = (*traces)[e.cell];
                    if (e.index + 1 >= tr.size()) continue;
                    if (scaled_norm(tr[e.index] - prev) >= kShadowTol || scaled_norm(tr[e.index + 1] - now) >= kShadowTol) continue;
                    if (!best || e.cell < best->cell || (e.cell == best->cell && e.index < best->index)) best = &e;
                }
            }
        return best ? &(*outcomes)[best->cell] : nullptr;
    }
};

CellOutcome run_cell(const Params& p, const BasinSpec& spec, const Vec2& y0, std::vector<CheckedCycle>& cache,
                     std::vector<Vec2>* trace = nullptr, const ShadowTable* table = nullptr) {
    CellOutcome out;
    const Drive d(spec.omega, 0.0, 0.0);
    Simulator sim(spec.sim);
    State s;
    s.x = y0[0];
    s.v = y0[1];
    Simulator::make_consistent(p, d, s);
    const int budget = spec.transient + spec.periods;
    // y[0] is the (consistent) start; y[i] the section point after i periods. Allocated before the loop.
    std::vector<Vec2> y(static_cast<std::size_t>(budget) + 1);
    std::vector<char> flew(static_cast<std::size_t>(budget) + 1, 1);
    y[0] = s.regime == Regime::Free ? Vec2(s.x, s.v) : Vec2(p.xI, 0.0);
    FreeWatch watch;
    int k = 0;
    int i = 1;
    try {
        for (; i <= budget; ++i) {
            watch.flew = false;
            sim.advance(p, d, s, d.time_of_phase(kTwoPi * i), &watch);
            y[static_cast<std::size_t>(i)] = s.regime == Regime::Free ? Vec2(s.x, s.v) : Vec2(p.xI, 0.0);
            flew[static_cast<std::size_t>(i)] = watch.flew ? 1 : 0;
            if (table && i >= 2) {
                const CellOutcome* known = table->follow(y[static_cast<std::size_t>(i) - 1], y[static_cast<std::size_t>(i)]);
                if (known && known->kind != AttractorKind::Failed) {
                    out = *known;
                    out.periods_run = i;
                    return out;
                }
            }
            k = recurrence(y, static_cast<std::size_t>(i) + 1, spec.max_period, spec.confirm, 4, spec.recur_tol);
            if (k > 0 && cycle_stable(p, spec, y, static_cast<std::size_t>(i) + 1, k, cache)) break;
            k = 0;
        }
    } catch (const SimulationStalled&) {
        out.kind = AttractorKind::Failed;
        out.periods_run = i;
        return out;
    }
    const std::size_t n = static_cast<std::size_t>(std::min(i, budget)) + 1;
    out.periods_run = static_cast<int>(n) - 1;
    if (trace) trace->assign(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(n));
    // A cycle that converges slowly (a multiplier near the unit circle) may not reach recur_tol within the
    // budget; it still repeats to within match_tol, and over the whole recorded window, which a chaotic
    // trajectory lingering near a saddle cycle for a few turns does not.
    if (k == 0) {
        k = recurrence(y, n, spec.max_period, spec.confirm, spec.periods, spec.match_tol);
        if (k > 0 && !cycle_stable(p, spec, y, n, k, cache)) k = 0;
    }
    if (k > 0) {
        // A period-1 orbit approached with a negative multiplier recurs at k = 2 before k = 1: the cycle is
        // reduced to the smallest divisor of k over which its own points repeat (to match_tol).
        for (int sub = 1; sub < k; ++sub) {
            if (k % sub != 0) continue;
            bool repeats = true;
            for (std::size_t j = n - 1; j + static_cast<std::size_t>(k - sub) >= n && repeats; --j)
                repeats = scaled_norm(y[j] - y[j - static_cast<std::size_t>(sub)]) < spec.match_tol;
            if (repeats) {
                k = sub;
                break;
            }
        }
        out.kind = AttractorKind::Periodic;
        out.period = k;
        out.points.assign(y.begin() + static_cast<std::ptrdiff_t>(n) - k, y.begin() + static_cast<std::ptrdiff_t>(n));
        const bool held = std::none_of(flew.begin() + static_cast<std::ptrdiff_t>(n) - k, flew.begin() + static_cast<std::ptrdiff_t>(n),
                                       [](char f) { return f != 0; });
        if (held) out.kind = AttractorKind::Resting;
        return out;
    }
    out.kind = AttractorKind::Chaos;
    const std::size_t keep = std::min(n - 1, static_cast<std::size_t>(spec.periods));
    out.points.assign(y.begin() + static_cast<std::ptrdiff_t>(n - keep), y.begin() + static_cast<std::ptrdiff_t>(n));
    return out;
}

}  // namespace

CellOutcome run_to_attractor(const Params& p, const BasinSpec& spec, const Vec2& y0) {
    std::vector<CheckedCycle> cache;
    return run_cell(p, spec, y0, cache);
}

bool same_attractor(const CellOutcome& a, const CellOutcome& b, const BasinSpec& spec) {
    if (a.kind != b.kind) return false;
    switch (a.kind) {
        case AttractorKind::Failed: return true;
        case AttractorKind::Periodic:
        case AttractorKind::Resting:
            // The same cycle: the same period and every point of one within match_tol of a point of the other.
            if (a.period != b.period) return false;
            for (const auto& q : a.points)
                if (nearest(q, b.points) >= spec.match_tol) return false;
            for (const auto& q : b.points)
                if (nearest(q, a.points) >= spec.match_tol) return false;
            return true;
        case AttractorKind::Chaos:
            // Two finite samples of one strange attractor never coincide; they lie close to each other
            // everywhere (median nearest-neighbour distance, both ways), two different attractors do not.
            if (a.points.empty() || b.points.empty()) return a.points.empty() && b.points.empty();
            return median_nearest(a.points, b.points) < spec.chaos_tol && median_nearest(b.points, a.points) < spec.chaos_tol;
    }
    return false;
}

BasinResult compute_basins(const Params& p, const BasinSpec& spec, Progress* progress) {
    validate(spec);
    const auto t_start = std::chrono::steady_clock::now();
    BasinResult res;
    res.spec = spec;
    const std::size_t nx = static_cast<std::size_t>(spec.nx), nv = static_cast<std::size_t>(spec.nv);
    std::vector<CellOutcome> cells(nx * nv);
    std::vector<char> done(nx * nv, 0);
    int threads = spec.threads > 0 ? spec.threads : static_cast<int>(std::thread::hardware_concurrency());
    threads = std::clamp(threads, 1, std::max(1, spec.nv));
    res.threads = threads;

    // Two passes. The coarse cells (every kCoarseStride-th in x and v) run to their attractors and keep their
    // section points; then every other cell runs until it recurs or follows a coarse trajectory for two
    // periods, whose end it shares (neighbours mostly converge to the same orbit: A1G at 13 rad/s needs a
    // fifth of the periods). Rows are handed out one at a time: chaotic rows cost ten times periodic ones, so
    // a static split would leave a thread idle. Each cell is written by exactly one thread; join() publishes.
    auto coarse = [](int i, int j) { return i % kCoarseStride == 0 && j % kCoarseStride == 0; };
    std::vector<std::vector<Vec2>> traces(nx * nv);
    ShadowTable table;
    table.traces = &traces;
    table.outcomes = &cells;
    std::atomic<int> next_row{0}, rows_done{0};
    std::exception_ptr error;
    std::mutex error_mutex;
    auto cancelled = [&] { return progress && progress->cancel.load(std::memory_order_relaxed); };
    const int coarse_rows = (spec.nv + kCoarseStride - 1) / kCoarseStride;
    auto run_pass = [&](bool first) {
        next_row.store(0);
        auto worker = [&] {
            std::vector<CheckedCycle> cache;
            try {
                for (int r; (r = next_row.fetch_add(1, std::memory_order_relaxed)) < (first ? coarse_rows : spec.nv);) {
                    const int j = first ? r * kCoarseStride : r;
                    for (int i = 0; i < spec.nx; ++i) {
                        if (coarse(i, j) != first) continue;
                        if (cancelled()) return;
                        const std::size_t c = static_cast<std::size_t>(j) * nx + static_cast<std::size_t>(i);
                        cells[c] = first ? run_cell(p, spec, Vec2(res.x0(i), res.v0(j)), cache, &traces[c])
                                         : run_cell(p, spec, Vec2(res.x0(i), res.v0(j)), cache, nullptr, &table);
                        done[c] = 1;
                    }
                    const int finished = rows_done.fetch_add(1, std::memory_order_relaxed) + 1;
                    if (progress)
                        progress->fraction.store(static_cast<double>(finished) / (coarse_rows + spec.nv), std::memory_order_relaxed);
                }
            } catch (...) {
                const std::lock_guard<std::mutex> lock(error_mutex);
                if (!error) error = std::current_exception();
                next_row.store(spec.nv, std::memory_order_relaxed);   // the others stop at their next row
            }
        };
        std::vector<std::thread> pool;
        pool.reserve(static_cast<std::size_t>(threads - 1));
        for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
        worker();
        for (auto& t : pool) t.join();
    };
    run_pass(true);
    if (!error && !cancelled()) {
        for (std::size_t c = 0; c < cells.size(); ++c)
            if (done[c] && cells[c].kind != AttractorKind::Failed)
                for (std::size_t k = 0; k < traces[c].size(); ++k)
                    table.insert(static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(k), traces[c][k]);
        run_pass(false);
    }
    if (error) std::rethrow_exception(error);
    res.cancelled = cancelled();

    // Labels in cell order: attractor ids follow the first cell that reached them, whatever ran where.
    res.label.assign(nx * nv, -1);
    std::vector<double> period_sum;
    for (std::size_t c = 0; c < cells.size(); ++c) {
        if (!done[c]) continue;
        res.periods_run += static_cast<std::uint64_t>(cells[c].periods_run);
        int id = -1;
        for (const auto& a : res.attractors)
            if (same_attractor(cells[a.first_cell], cells[c], spec)) {
                id = a.id;
                break;
            }
        if (id < 0) {
            Attractor a;
            a.id = static_cast<int>(res.attractors.size());
            a.kind = cells[c].kind;
            a.period = cells[c].period;
            a.points = cells[c].points;
            a.first_cell = c;
            if (!a.points.empty()) {
                double mean_x = 0;
                for (const auto& q : a.points) mean_x += q[0];
                mean_x /= static_cast<double>(a.points.size());
                a.well = mean_x < -1e-9 ? -1 : mean_x > 1e-9 ? 1 : 0;
                a.representative = *std::min_element(a.points.begin(), a.points.end(),
                                                     [](const Vec2& u, const Vec2& w) { return u[0] < w[0]; });
            }
            res.attractors.push_back(std::move(a));
            period_sum.push_back(0);
            id = res.attractors.back().id;
        }
        res.label[c] = id;
        ++res.attractors[static_cast<std::size_t>(id)].cells;
        period_sum[static_cast<std::size_t>(id)] += cells[c].periods_run;
    }
    for (auto& a : res.attractors)
        a.mean_periods = a.cells ? period_sum[static_cast<std::size_t>(a.id)] / static_cast<double>(a.cells) : 0.0;
    res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    return res;
}

void set_default_window(const Params& p, BasinSpec& spec) {
    const double x_hi = p.has_bumper() ? std::min(p.xI, 0.03) : 0.03;
    spec.x_min = std::min(-0.03, x_hi - 0.03);
    spec.x_max = x_hi;
    spec.v_min = -0.3;
    spec.v_max = 0.3;
}

}  // namespace impactlab::analysis
