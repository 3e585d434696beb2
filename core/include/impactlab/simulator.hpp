// The hybrid simulator: regimes I (free flight), II (sticking during a rigid impact) and III (permanent
// contact) over the RODAS4 stepper, with events located on the dense output and then hit exactly.
// Parameters stay apart from state: step(const Params&, const Drive&, State&, ...). Nothing allocates in
// the step loop. All functions are called on the thread that owns the State (the simulation thread in
// the GUI, the worker in a sweep, the main thread in the CLI).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>

#include "impactlab/drive.hpp"
#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"

namespace impactlab {

enum class Regime : std::uint8_t { Free = 1, Sticking = 2, Contact = 3 };   // I, II, III
const char* regime_name(Regime r);

struct State {
    double t = 0, x = 0, v = 0;          // [s], [m], [m/s]
    Regime regime = Regime::Free;
    double t_release = 0;                // regime II: when the sticking ends [s]
    double v_release = 0;                // regime II: the velocity v+ it ends with [m/s]
    double v_impact = 0;                 // regime II: the velocity v- of the impact in progress [m/s]
    double h = 0;                        // next step-size guess [s]; 0 lets the simulator choose
    std::int64_t next_section = 1;       // n of the next Poincare section (Simulator::section_phi)
    std::int8_t side = 0;                // compliant bumper: +1 in contact, -1 clear, 0 unknown
    std::uint64_t steps = 0, rejected = 0, impacts = 0;
    double t_mark = 0;                   // the step budget's last checkpoint: time and steps + rejected there
    std::uint64_t steps_mark = 0;
};

// A run that exceeded its step or wall-clock budget (Tolerances): the message names the regime, t and the
// step size, and what to look at. Thrown by Simulator::step/advance on the simulating thread.
struct SimulationStalled : std::runtime_error { using std::runtime_error::runtime_error; };
inline constexpr std::uint64_t kStallWindow = 1u << 16;   // steps between two checks of the step budget

// n counts the unbalance's revolutions: section n is the one in phi in (2 pi (n - 1), 2 pi n]
// (Simulator::section_phi), so a run from phi = 0 meets sections 1, 2, ... whatever the section phase.
struct SectionPoint { std::int64_t n; double t, x, v; Regime regime; };
struct ImpactEvent { double t, v_minus, v_plus, duration; };

// A stretch of trajectory the simulator has just completed: (x, v) anywhere in [t0, t1].
struct Piece {
    double t0, t1;
    Regime regime;
    const DenseStep* step;   // free flight: the accepted step; null while held at the bumper
    double x_hold;           // regimes II/III: the bumper position
    Vec2 at(double t) const { return step ? step->at(t) : Vec2(x_hold, 0.0); }
};

// Receives what happens, in time order, on the simulating thread. Default: ignore.
class Observer {
public:
    virtual ~Observer() = default;
    virtual void on_piece(const Piece&) {}
    virtual void on_section(const SectionPoint&) {}
    virtual void on_impact(const ImpactEvent&) {}
    virtual void on_regime(double /*t*/, Regime /*from*/, Regime /*to*/) {}
    virtual bool stop() const { return false; }   // true: advance() returns after the current piece
};

class Simulator {
public:
    explicit Simulator(const Tolerances& tol = {}) : tol_(tol) {}
    const Tolerances& tolerances() const { return tol_; }
    void set_tolerances(const Tolerances& tol) { tol_ = tol; }

    // The Poincare section phase phi0 [rad], 0 <= phi0 <= 2 pi (2 pi is 0): sections at phi = phi0 + 2 pi k.
    // An analysis setting, not physics: it changes which instants on_section reports, never the
    // trajectory. Throws std::invalid_argument outside the range. Default 0: the stroboscopic phi = 2 pi n.
    // Changed mid-run, sync_sections(d, s) must follow: the revolution running may have its new section ahead.
    void set_section_phase(double phi0);
    double section_phase() const { return phi0_; }
    // The phase of section n: 2 pi n for phi0 = 0 (or 2 pi), else 2 pi (n - 1) + phi0; either way the
    // last section at or before phi = 2 pi n, so sync_sections (which counts revolutions) needs no phase.
    double section_phi(std::int64_t n) const { return kTwoPi * static_cast<double>(n) - psi_; }
    // When the next section after s.t comes under drive d (infinite for a drive that stops short of it).
    double next_section_time(const Drive& d, const State& s) const;

    // Makes a state consistent with the parameters and the drive: a rigid bumper never has the cart beyond
    // xI (it is put on the bumper, in regime III if the normal force presses it there, else I); compliant
    // models only know regime I; the next Poincare section is the first after state.t.
    static void make_consistent(const Params& p, const Drive& d, State& s);
    // Moves the bumper to xI quasi-statically: if it lands on the cart it pushes the cart back to the
    // contact point and stops it there (so a compliant bumper never starts deep inside the cart); a
    // sticking in progress ends, since the bumper no longer holds the cart where the impact left it. A
    // compliant bumper already pressed h deep keeps that depth (a move by zero changes nothing).
    // Then make_consistent settles the regime.
    static void move_bumper(Params& p, const Drive& d, State& s, double xI);
    // After a change of drive only: the next section becomes that of the first revolution ending after s.t
    // (step() passes over it if the section phase put it at or before s.t); a regime II or III in
    // progress carries over.
    static void sync_sections(const Drive& d, State& s);

    // One piece: an accepted integration step, a located event, or a stretch held at the bumper; never
    // past t_limit. Returns false if nothing could be done (t_limit reached). Throws SimulationStalled
    // past the step budget.
    bool step(const Params& p, const Drive& d, State& s, double t_limit, Observer* obs = nullptr);
    // Steps until s.t == t_end or the observer asks to stop. Throws SimulationStalled past the budgets.
    void advance(const Params& p, const Drive& d, State& s, double t_end, Observer* obs = nullptr);

private:
    bool free_step(const Params& p, const Drive& d, State& s, double t_stop, Observer* obs);
    void hold_step(const Params& p, const Drive& d, State& s, double t_stop, Observer* obs);
    void release(const Params& p, const Drive& d, State& s, double v_plus, Observer* obs);
    void check_step_budget(State& s) const;
    Tolerances tol_;
    double phi0_ = 0;   // the section phase [rad]
    double psi_ = 0;    // 2 pi - phi0 (0 for phi0 = 0): how far section n lies before phi = 2 pi n [rad]
    DenseStep work_, retry_;
    // First-same-as-last cache of the explicit method: f at (fsal_t_, fsal_y_).
    bool fsal_valid_ = false, in_advance_ = false;
    double fsal_t_ = 0;
    Vec2 fsal_y_ = Vec2::Zero(), fsal_f_ = Vec2::Zero();
};

// Normal force pressing the cart on the bumper at xI while it rests there [N] (positive: pressed).
double normal_force(const Params& p, const Drive& d, double t);
// Total mechanical energy 1/2 m v^2 + V(x) (+ the bumper's elastic energy for compliant models) [J].
double mechanical_energy(const Params& p, double x, double v);
// Its last term: kI h^(n1+1) / (n1+1) at the compliant bumper's penetration h = x - xI > 0, else 0 [J].
double bumper_elastic_energy(const Params& p, double x);
// The force the bumper exerts at this instant [N]: F_I (compliant), N (regime III), the mean force of the
// impulse (regime II), else 0.
double bumper_force(const Params& p, const Drive& d, const State& s);

// The force terms of Eq. (1) at one instant without the input (rig_forces, rig.hpp); the residual and the GUI
// use them. net() sums them in the order the fit's equation error always has, so its reports stay the same.
struct ForceTerms {
    double resistance = 0, spring_magnet = 0, impact = 0, unbalance = 0, effects = 0;
    double net() const { return unbalance + effects - resistance - spring_magnet - impact; }
};
ForceTerms force_terms(const Params& p, double t, double x, double v, double phi, double omega, double alpha);

// Observer that samples the trajectory at a fixed step dt (from t_first) and hands each sample to a callback.
struct Sample { double t, x, v, phi, omega; Regime regime; };
class UniformSampler : public Observer {
public:
    UniformSampler(const Drive& d, double dt, double t_first, std::function<void(const Sample&)> sink)
        : drive_(d), dt_(dt), t_first_(t_first), next_(t_first), sink_(std::move(sink)) {}
    void on_piece(const Piece& piece) override;
private:
    const Drive& drive_;
    double dt_;
    double t_first_;
    double next_;
    std::int64_t k_ = 0;
    std::function<void(const Sample&)> sink_;
};

}  // namespace impactlab
