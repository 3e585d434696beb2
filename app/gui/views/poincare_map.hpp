// The Poincare map as the visualiser shows it: a settle detector over the incoming section points. After
// every change of the dynamics (reset()) all points are transient; the map decides the period k (1..N)
// once the newest points recur after k periods within a tolerance relative to the attractor's size, or
// "chaos" once enough points show no recurrence, and keeps only the points from then on. A periodic orbit
// that breaks (a drift, a slow transient that had looked settled) sends it back to settling; one found
// after chaos had been said must hold longer, and sends it back to chaos when it breaks.
// A period k is re-checked against every new point: a period-1 orbit with a negative multiplier
// approaches it alternating, and P^2 recurs long before P does, so a k whose divisor d recurs later
// becomes d; and k is not said while the d-differences are still shrinking (the alternation dying out).
// While undecided for provisional_after points the newer half is shown as provisional (no period said).
// GL-free; UI thread only (the app feeds it from its drain of the sample ring).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sim/history.hpp"
#include "sim/sim_messages.hpp"

namespace impactlab::gui {

struct PoincareConfig {
    int max_period = 32;          // the largest period recognised; beyond it an orbit reads as chaos
                                  // (A3C at 18.1608 rad/s has a stable period 24, lambda_max < 0)
    double rel_tol = 1e-3;        // recurrence: |dx| / size_x and |dv| / size_v both below this
    double hold_factor = 2;       // a settled orbit breaks when a point misses by hold_factor * rel_tol: a
                                  // settled orbit recurs at the integrator's accuracy, far below rel_tol, while
                                  // a period 24 passed off as its unstable period 12 misses by 4 (A3C, 18.1608)
    double loose_factor = 10;     // a dying alternation's stretch: recurring within loose_factor * rel_tol
    int chaos_after = 64;         // section points without any recurrence before "chaos" is said
    int provisional_after = 16;   // undecided points before the newer half is shown (no period said)
    int periodic_cycles = 4;      // a periodic orbit shows its last few cycles: where it is, not where it
                                  // was while it converged (a slow approach would smear each point)
    double min_size_x = 1e-3;     // [m]   floors of the attractor's size (a cart at rest has size 0)
    double min_size_v = 1e-2;     // [m/s]
    std::size_t capacity = std::size_t{1} << 17;   // points kept on the map (power of two)
};

// One section point and what happened in the forcing period that ended at it.
struct MapInput {
    double t = 0;                 // [s] the section's time
    double x = 0, v = 0;          // [m], [m/s] at phi = 2 pi n
    int impacts = 0;              // impacts on the bumper during the period
    double size_x = 0, size_v = 0;   // the trajectory's extent over that period (the attractor's size)
};

struct MapPoint {
    double x = 0, v = 0;
    int impacts = 0;
};

class PoincareMap {
public:
    enum class Status { Settling, Periodic, Chaotic };

    explicit PoincareMap(const PoincareConfig& cfg = {});

    // A change of the dynamics (preset, omega, xI, model, reset) or the user's "clear": all is transient.
    void reset();
    void push(const MapInput& in);

    Status status() const { return status_; }
    const PoincareConfig& config() const { return cfg_; }
    // Settling, but showing the newest undecided points (the transient has had provisional_after periods).
    bool provisional() const { return status_ == Status::Settling && !points_.empty(); }
    // The period k while Periodic; 0 while Chaotic; -1 while settling.
    int period() const { return status_ == Status::Periodic ? period_ : status_ == Status::Chaotic ? 0 : -1; }
    // Settling on an alternation that recurs after k periods but is still dying out (a multiplier near -1):
    // the period is a divisor of k, not yet known. decay() is the alternation's shrink per forcing period
    // (its |multiplier|, e.g. 0.994), NaN when unknown.
    bool slow() const { return status_ == Status::Settling && slow_; }
    double decay() const { return decay_; }
    // Section points received since the last reset() (transient included).
    std::uint64_t seen() const { return seen_; }
    // The settled points, oldest first: a periodic orbit's last periodic_cycles * k, a chaotic orbit's all
    // since the decision (up to the capacity); while settling, empty or the provisional points. Its generation() changes whenever the map
    // starts over (a reset, a new period or chaos decided), which is when an auto-fit should snap.
    const History<MapPoint>& points() const { return points_; }
    // The recurrence tolerance now in force [m], [m/s] (rel_tol times the attractor's size).
    double tol_x() const { return tol_x_; }
    double tol_v() const { return tol_v_; }
    // Every input since the last reset(), oldest first (up to the capacity: beyond it the oldest go).
    const History<MapInput>& inputs() const { return inputs_; }
    // Replay: makes this map what `live` was once its inputs up to time t [s] had arrived, by feeding them
    // again (the same decisions, the same points). Moving forward only feeds the new ones; going back starts
    // over. Exact unless `live` has dropped inputs (more than the capacity since its reset).
    void replay(const PoincareMap& live, double t);

private:
    void update_tolerance();
    bool recurs(std::size_t i, std::size_t k, double factor) const;   // recent_[i] vs recent_[i - k]
    // The smallest period below `below` (that divides it, when `divisors`) recurring over its confirmations
    // and at least `at_least` points; 0 if none.
    int find_period(std::size_t at_least, int below, bool divisors) const;
    double gap(std::size_t i, std::size_t d) const;   // recent_[i] vs recent_[i - d] in tolerances
    bool dying_alternation(int k) const;
    void settle_on(int k);
    void declare_chaos();

    PoincareConfig cfg_;
    std::vector<MapInput> recent_;   // the newest points since the last reset, at most window_ of them
    std::size_t window_;
    History<MapPoint> points_;
    History<MapInput> inputs_;
    // replay(): what this map was last fed from, and how much of it.
    const PoincareMap* replay_of_ = nullptr;
    std::uint64_t replay_generation_ = 0, replay_fed_seq_ = 0;
    Status status_ = Status::Settling;
    int period_ = 0;
    std::uint64_t seen_ = 0;
    std::uint64_t unsettled_ = 0;    // points since the last reset or break without a decision
    double tol_x_ = 0, tol_v_ = 0;
    bool from_chaos_ = false;        // the current period was found after chaos had been said
    bool slow_ = false;              // the last point recurred after k > 1 periods, its alternation dying
    mutable double decay_ = NAN;     // the alternation's shrink per period when last measured (dying_alternation)
};

// Turns the simulation's records, in the order they were published, into MapInputs: the extent of the
// samples and the impacts between two section points go with the second. Impacts are the rigid impacts
// the engine reports (G, H) or, for the compliant laws, the samples where the bumper force switches on,
// whichever is more. UI thread (the app's drain), or the test's thread.
class SectionFeeder {
public:
    void reset();   // with PoincareMap::reset(): the period in progress belongs to the old dynamics
    void on_msg(const SimMsg& m, PoincareMap& map);

private:
    double x_lo_ = 0, x_hi_ = 0, v_lo_ = 0, v_hi_ = 0;
    bool have_ = false;
    bool in_contact_ = false;
    int impacts_ = 0, onsets_ = 0;
};

}  // namespace impactlab::gui
