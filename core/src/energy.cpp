#include "impactlab/energy.hpp"

#include <algorithm>
#include <cmath>

#include "impactlab/forces.hpp"

namespace impactlab {

namespace {
// 5-point Gauss-Legendre on [-1, 1]: the powers are smooth within a piece (the simulator ends pieces at every
// contact, sticking and release), and a piece spans a small part of a forcing period.
constexpr double kNodes[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                              0.9061798459386640};
constexpr double kWeights[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                0.2369268850561891};
}  // namespace

double EnergyBalance::turnover() const {
    return std::abs(E0) + std::abs(E) + std::abs(work_unbalance) + std::abs(work_effects) +
           std::abs(dissipated_resistance) + std::abs(dissipated_bumper);
}

void EnergyLedger::reset(const State& s) {
    b_ = EnergyBalance{};
    b_.t0 = b_.t = s.t;
    b_.E0 = b_.E = mechanical_energy(*p_, s.x, s.v);
    b_.x = s.x;
    b_.v = s.v;
    bumper_work_ = jump_loss_ = 0;
    elastic0_ = bumper_elastic_energy(*p_, s.x);
    started_ = true;
}

void EnergyLedger::on_piece(const Piece& piece) {
    const Params& p = *p_;
    const Drive& d = *d_;
    const Vec2 y0 = piece.at(piece.t0);
    if (!started_) reset(State{piece.t0, y0[0], y0[1]});
    // A jump between pieces is a rigid impact (v- to 0 or to v+) or a release (0 to v+): the energy it takes
    // or gives back is the bumper's. b_ holds where the last piece ended, and E there.
    if (y0[0] != b_.x || y0[1] != b_.v) jump_loss_ += b_.E - mechanical_energy(p, y0[0], y0[1]);
    if (piece.step && piece.t1 > piece.t0) {   // held at the bumper (v = 0) no force does work
        const double half = 0.5 * (piece.t1 - piece.t0), mid = 0.5 * (piece.t1 + piece.t0);
        for (int i = 0; i < 5; ++i) {
            const double t = mid + half * kNodes[i];
            const Vec2 y = piece.at(t);
            const double w = d.omega(t), phi = d.phi(t);
            const ForceTerms f = force_terms(p, t, y[0], y[1], phi, w, d.alpha(t));
            double drive = p.m0e != 0.0 ? f.unbalance : 0.0;
            if (p.input_gain != 0.0) drive += p.input_gain * d.input(t);
            const double wv = kWeights[i] * half * y[1];
            b_.work_unbalance += drive * wv;
            b_.work_effects += f.effects * wv;
            b_.dissipated_resistance += f.resistance * wv;
            bumper_work_ += f.impact * wv;
        }
    }
    const Vec2 y1 = piece.at(piece.t1);
    b_.t = piece.t1;
    b_.x = y1[0];
    b_.v = y1[1];
    b_.E = mechanical_energy(p, y1[0], y1[1]);
    b_.dissipated_bumper = jump_loss_;
    if (p.compliant()) b_.dissipated_bumper += bumper_work_ - (bumper_elastic_energy(p, y1[0]) - elastic0_);
}

}  // namespace impactlab
