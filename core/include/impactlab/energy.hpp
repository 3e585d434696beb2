// The energy balance of a run, kept along the trajectory the Simulator reports:
//   E(t) - E(t0) = W_unbalance + W_effects - D_resistance - D_bumper,
// with E the mechanical energy (kinetic, springs and magnets, and a compliant bumper's elastic energy).
// Each term is a quadrature of its own power over the simulator's pieces (dense output), never the balance's
// remainder, so residual() measures how well the balance closes. Used by the visualiser's energy bar and by
// the tests' energy invariants. Called on the thread that runs the Simulator.
#pragma once

#include "impactlab/drive.hpp"
#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab {

struct EnergyBalance {
    double t0 = 0, t = 0;              // [s] the stretch the balance covers
    double E0 = 0, E = 0;              // mechanical energy at t0 and at t [J]
    double x = 0, v = 0;               // the state at t [m], [m/s] (E's kinetic share is m v^2 / 2)
    double work_unbalance = 0;         // work of the unbalance's force (and of a measured input) [J]
    double work_effects = 0;           // work of the added effects; negative where they dissipate [J]
    double dissipated_resistance = 0;  // by the bearing resistance F_R(v) = c v + T v / sqrt(v^2 + eps^2) [J]
    double dissipated_bumper = 0;      // at the bumper: the kinetic energy rigid impacts take, or the
                                       // compliant contact's hysteresis (work of F_I less its elastic energy) [J]
    // How far the balance is from closing [J]: 0 up to the integration and quadrature error.
    double residual() const {
        return (E - E0) - (work_unbalance + work_effects - dissipated_resistance - dissipated_bumper);
    }
    // The scale the residual is judged against [J]: all the energy that flowed.
    double turnover() const;
};

// An Observer that keeps the balance. Params and Drive are held by reference and must outlive it; after a
// change of either (or of the state from outside the Simulator) call reset() to begin a new balance.
class EnergyLedger : public Observer {
public:
    EnergyLedger(const Params& p, const Drive& d) : p_(&p), d_(&d) {}
    void rebind(const Params& p, const Drive& d) { p_ = &p; d_ = &d; }
    // Begins a new balance at this state: all terms 0, E0 = E(state).
    void reset(const State& s);
    void on_piece(const Piece& piece) override;
    const EnergyBalance& balance() const { return b_; }

private:
    const Params* p_;
    const Drive* d_;
    EnergyBalance b_;
    double jump_loss_ = 0;           // energy taken by the jumps between pieces (rigid impacts) [J]
    double bumper_work_ = 0;         // integral of F_I v over the compliant contact [J]
    double elastic0_ = 0;            // the bumper's elastic energy at t0 [J]
    bool started_ = false;
};

}  // namespace impactlab
