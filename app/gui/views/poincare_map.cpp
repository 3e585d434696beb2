#include "poincare_map.hpp"

#include <algorithm>
#include <cmath>

namespace impactlab::gui {

namespace {
// Recurrences a period k needs before it is believed: every one of the k points has come back twice, and
// never fewer than six in a row (a chaotic orbit lingering near an unstable fixed point rarely does that).
std::size_t confirmations(std::size_t k) { return std::max<std::size_t>(2 * k + 2, 6); }
}  // namespace

PoincareMap::PoincareMap(const PoincareConfig& cfg)
    : cfg_(cfg),
      // dying_alternation needs a recurring stretch of four cycles behind the first k points: 5k in all,
      // or the longest periods (15 and 16) could never be said and a stable period 16 read as chaos.
      window_(std::max<std::size_t>(5 * static_cast<std::size_t>(cfg.max_period) + 2,
                                    static_cast<std::size_t>(cfg.chaos_after)) + 8),
      points_(cfg.capacity),
      inputs_(cfg.capacity) {
    recent_.reserve(window_ + 1);
    update_tolerance();
}

void PoincareMap::reset() {
    recent_.clear();
    points_.clear();
    inputs_.clear();
    replay_of_ = nullptr;
    from_chaos_ = false;
    status_ = Status::Settling;
    period_ = 0;
    seen_ = 0;
    unsettled_ = 0;
    slow_ = false;
    decay_ = NAN;
    update_tolerance();
}

void PoincareMap::update_tolerance() {
    // The attractor's size: the largest extent of a period over the recent points.
    double sx = cfg_.min_size_x, sv = cfg_.min_size_v;
    for (const MapInput& p : recent_) {
        sx = std::max(sx, p.size_x);
        sv = std::max(sv, p.size_v);
    }
    tol_x_ = cfg_.rel_tol * sx;
    tol_v_ = cfg_.rel_tol * sv;
}

bool PoincareMap::recurs(std::size_t i, std::size_t k, double factor) const {
    const MapInput& a = recent_[i];
    const MapInput& b = recent_[i - k];
    return std::abs(a.x - b.x) <= factor * tol_x_ && std::abs(a.v - b.v) <= factor * tol_v_;
}

int PoincareMap::find_period(std::size_t at_least, int below, bool divisors) const {
    const std::size_t n = recent_.size();
    // The smallest k wins: a period-2 orbit also recurs after 4 periods.
    for (std::size_t k = 1; k < static_cast<std::size_t>(below); ++k) {
        if (divisors && static_cast<std::size_t>(below) % k != 0) continue;
        const std::size_t r = std::max(confirmations(k), at_least);
        if (n < r + k) break;   // larger k need even more points
        bool all = true;
        for (std::size_t i = n - r; i < n && all; ++i) all = recurs(i, k, 1.0);
        if (all) return static_cast<int>(k);
    }
    return 0;
}

double PoincareMap::gap(std::size_t i, std::size_t d) const {
    const MapInput& a = recent_[i];
    const MapInput& b = recent_[i - d];
    return std::max(std::abs(a.x - b.x) / tol_x_, std::abs(a.v - b.v) / tol_v_);
}

bool PoincareMap::dying_alternation(int period) const {
    // Over the trailing stretch where P^k recurs (loosely), the d-difference (d | k) of a transient converging
    // to period d shrinks geometrically to 0, that of a period-k orbit levels off at the orbit's own spread.
    // Which one: the spread's shrink per period over the newer half of the stretch.
    const auto k = static_cast<std::size_t>(period);
    const std::size_t n = recent_.size();
    std::size_t first = n;
    while (first > k && recurs(first - 1, k, cfg_.loose_factor)) --first;
    // Samples over the newer half of the stretch, whole cycles apart: the older half still holds the faster
    // modes and the nonlinear start, which make an early decay look as if it levelled off.
    const std::size_t m = (n - first) / (4 * k) * k;
    for (std::size_t d = 1; d < k; ++d) {
        if (k % d != 0 || first < d) continue;
        if (m == 0) return true;   // too short a stretch to tell: wait (four cycles)
        const auto spread = [&](std::size_t end) {   // the largest d-difference over the cycle ending at end
            double g = 0;
            for (std::size_t j = 0; j < k; ++j) g = std::max(g, gap(end - j, d));
            return g;
        };
        const double eb = spread(n - 1 - m), ec = spread(n - 1);
        if (ec - eb > -0.05) continue;                // not shrinking (by more than noise)
        // Still shrinking measurably: not period k yet. Near a multiplier of -1 the alternation dies out over
        // hundreds of periods (0.64 % a period at A1H's 10.85 rad/s), and an extrapolation from a few samples
        // (a fast mode dying on top of it) once took it for a level and said period 2. A period-k orbit's own
        // spread is level: its shrink per period falls below kLevel once it has converged.
        constexpr double kLevel = 2e-4;               // [1/period] a shrink this slow is a level
        if (std::log(eb / ec) / static_cast<double>(m) < kLevel) continue;
        decay_ = eb > 0 && ec > 0 ? std::pow(ec / eb, 1.0 / static_cast<double>(m)) : NAN;
        return true;
    }
    return false;
}

void PoincareMap::settle_on(int k) {
    // Only the last k points: one per point of the orbit, each within the tolerance of where it recurs.
    status_ = Status::Periodic;
    period_ = k;
    unsettled_ = 0;
    points_.clear();
    for (std::size_t i = recent_.size() - static_cast<std::size_t>(k); i < recent_.size(); ++i)
        points_.push({recent_[i].x, recent_[i].v, recent_[i].impacts});
}

void PoincareMap::declare_chaos() {
    // No recurrence can tell where a chaotic transient ends: the older half of the undecided points is
    // dropped as transient, the newer half starts the map.
    status_ = Status::Chaotic;
    period_ = 0;
    from_chaos_ = false;
    if (!points_.empty()) return;   // the provisional points go on (no jump of the view)
    const std::size_t keep = std::min(recent_.size(), static_cast<std::size_t>(cfg_.chaos_after) / 2);
    for (std::size_t i = recent_.size() - keep; i < recent_.size(); ++i)
        points_.push({recent_[i].x, recent_[i].v, recent_[i].impacts});
}

void PoincareMap::replay(const PoincareMap& live, double t) {
    const History<MapInput>& in = live.inputs();
    // The inputs up to t: [0, end).
    const std::size_t end = in.lower_bound(std::nextafter(t, INFINITY), [](const MapInput& m) { return m.t; });
    const std::uint64_t end_seq = end < in.size() ? in.seq_of(end) : in.seq_of(0) + in.size();
    const bool go_on = replay_of_ == &live && replay_generation_ == in.generation() && replay_fed_seq_ <= end_seq &&
                       (in.empty() || replay_fed_seq_ >= in.seq_of(0));
    if (!go_on) {
        const PoincareMap* keep = &live;
        reset();
        replay_of_ = keep;
        replay_generation_ = in.generation();
        replay_fed_seq_ = in.empty() ? 0 : in.seq_of(0);
    }
    for (std::size_t i = static_cast<std::size_t>(replay_fed_seq_ - (in.empty() ? 0 : in.seq_of(0))); i < end; ++i) push(in[i]);
    replay_fed_seq_ = end_seq;
}

void PoincareMap::push(const MapInput& in) {
    inputs_.push(in);
    ++seen_;
    ++unsettled_;
    recent_.push_back(in);
    if (recent_.size() > window_) recent_.erase(recent_.begin());   // ~90 elements, once a forcing period
    update_tolerance();
    const std::size_t n = recent_.size();

    if (status_ == Status::Periodic) {
        const auto k = static_cast<std::size_t>(period_);
        if (n > k && recurs(n - 1, k, cfg_.hold_factor)) {
            unsettled_ = 0;
            points_.push({in.x, in.v, in.impacts});
            const std::size_t keep = k * static_cast<std::size_t>(std::max(cfg_.periodic_cycles, 1));
            if (points_.size() > keep) points_.drop_oldest(points_.size() - keep);
            // The alternation of a negative multiplier has died out: the orbit's period is a divisor of k.
            if (const int d = k > 1 ? find_period(0, period_, true) : 0; d > 0) settle_on(d);
            // Or it is still dying out (it looked level for a while): not period k after all, wait.
            else if (k > 1 && !from_chaos_ && dying_alternation(period_)) {
                status_ = Status::Settling;
                period_ = 0;
                unsettled_ = 1;
                slow_ = true;   // the points go on as provisional ones (no jump of the view)
            }
            return;
        }
        if (from_chaos_) {
            // A laminar phase of an intermittent chaotic orbit (it lingered near an unstable cycle): chaos
            // again at once rather than another wait of chaos_after periods.
            declare_chaos();
            return;
        }
        // The orbit left the cycle it seemed to have settled on: it was a slow transient after all.
        status_ = Status::Settling;
        period_ = 0;
        points_.clear();
        unsettled_ = 1;
    }
    // Out of chaos, a cycle must hold for half of chaos_after periods: chaotic orbits linger near their
    // unstable cycles for a few periods (intermittency), a settled orbit recurs for ever.
    const bool chaotic = status_ == Status::Chaotic;
    bool converging = false;
    slow_ = false;
    if (const int k = find_period(chaotic ? static_cast<std::size_t>(cfg_.chaos_after) / 2 : 0, cfg_.max_period + 1, false);
        k > 0) {
        if (!dying_alternation(k)) {
            settle_on(k);
            from_chaos_ = chaotic;
            return;
        }
        converging = true;   // recurring, so not chaos: the period is not yet known
        slow_ = k > 1;       // an alternation dying out: the period is a divisor of k, not yet known
    }
    if (status_ == Status::Chaotic) {
        points_.push({in.x, in.v, in.impacts});
        return;
    }
    if (!points_.empty()) points_.push({in.x, in.v, in.impacts});
    else if (unsettled_ >= static_cast<std::uint64_t>(cfg_.provisional_after)) {
        // Provisional: the newer half of the undecided points, the older half taken for the transient.
        const std::size_t keep = std::min(recent_.size(), static_cast<std::size_t>(unsettled_ / 2));
        for (std::size_t i = recent_.size() - keep; i < recent_.size(); ++i)
            points_.push({recent_[i].x, recent_[i].v, recent_[i].impacts});
    }
    if (!converging && unsettled_ >= static_cast<std::uint64_t>(cfg_.chaos_after)) declare_chaos();
}

void SectionFeeder::reset() {
    have_ = false;
    in_contact_ = false;
    impacts_ = onsets_ = 0;
}

void SectionFeeder::on_msg(const SimMsg& m, PoincareMap& map) {
    switch (m.kind) {
        case MsgKind::Sample: {
            if (!have_) {
                x_lo_ = x_hi_ = m.x;
                v_lo_ = v_hi_ = m.v;
                have_ = true;
            }
            x_lo_ = std::min(x_lo_, m.x);
            x_hi_ = std::max(x_hi_, m.x);
            v_lo_ = std::min(v_lo_, m.v);
            v_hi_ = std::max(v_hi_, m.v);
            const bool contact = m.force > 0;
            if (contact && !in_contact_) ++onsets_;
            in_contact_ = contact;
            break;
        }
        case MsgKind::Impact:
            ++impacts_;
            break;
        case MsgKind::Section: {
            MapInput in;
            in.t = m.t;
            in.x = m.x;
            in.v = m.v;
            in.impacts = std::max(impacts_, onsets_);
            if (have_) {
                in.size_x = x_hi_ - x_lo_;
                in.size_v = v_hi_ - v_lo_;
            }
            map.push(in);
            // The next period's extent starts at this point.
            x_lo_ = x_hi_ = m.x;
            v_lo_ = v_hi_ = m.v;
            have_ = true;
            impacts_ = onsets_ = 0;
            break;
        }
        case MsgKind::Grazing:   // the grazing monitor's summary: not the map's
            break;
    }
}

}  // namespace impactlab::gui
