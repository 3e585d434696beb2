// The variational (tangent) equation of the rig, carried along the Simulator's own trajectory.
//
// Why this is not a second integrator of the rig: the state (x, v) is never integrated here. TangentTracker
// is an Observer; the Simulator hands it each accepted piece with its dense output y(t), and the tracker
// integrates only the linear equation d(Phi)/dt = A(t) Phi with A = df/dy evaluated at that y(t) (Magnus
// order 6, order 4 where h A is large; adaptive). At the events the Simulator reports (impact, end of sticking, permanent contact) the
// tracker applies the saltation matrix of the impact law. So the trajectory, its events and the sections
// are exactly the Simulator's, and Phi is their derivative. A piece's propagators do not depend on Phi, so a
// period map (period_map) keeps the pieces and computes them afterwards on all cores, in the same order.
#pragma once

#include <algorithm>
#include <atomic>

#include <vector>

#include "impactlab/analysis.hpp"
#include "impactlab/drive.hpp"
#include "impactlab/params.hpp"
#include "impactlab/rosenbrock.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::analysis::detail {

// Acceleration of Eq. (1) at one instant (free flight; with a compliant bumper's force) [m/s^2].
double acceleration(const Params& p, const Drive& d, double t, double x, double v);
// The Jacobian A = df/dy of Eq. (1) at one instant (exact slopes, also the Hunt-Crossley damping's).
Mat2 jacobian(const Params& p, const Drive& d, double t, double x, double v);

// One Magnus step of Phi' = A(t) Phi over h: order 4 from A at the two Gauss points tm -+ sqrt(3)/6 h,
// order 6 (Blanes, Casas, Ros) from A at the three tm - sqrt(15)/10 h, tm, tm + sqrt(15)/10 h.
Mat2 magnus4_step(const Mat2& A1, const Mat2& A2, double h);
Mat2 magnus6_step(const Mat2& A1, const Mat2& A2, const Mat2& A3, double h);
constexpr double kGauss2 = 0.28867513459481287;   // sqrt(3)/6
constexpr double kGauss3 = 0.38729833462074170;   // sqrt(15)/10

// The contact's Magnus tolerance that matches a simulator tolerance: a tenth of rtol, within 1e-11..1e-9. The
// stiff bumper's contacts cost 7x fewer substeps at 1e-9 than at 1e-11 (A1C1's CF sweep at 12.75..16.5
// rad/s), and its exponents move by 1e-7 1/s.
inline double step_tol_for(double rtol) { return std::clamp(0.1 * rtol, 1e-11, 1e-9); }

class TangentTracker : public Observer {
public:
    TangentTracker(const Params& p, const Drive& d, bool tangent) : p_(p), d_(d), tangent_(tangent) {}

    Mat2 Phi = Mat2::Identity();          // d y(t) / d y(t_start), on the free-flight representation
    int impacts = 0;                      // rigid impacts and compliant contacts entered
    double max_x = -1e300;                // [m]
    double min_impact_speed = 1e300;      // [m/s]
    bool contact = false;                 // regime III met
    std::vector<Vec2>* sections = nullptr;   // optional: each section's (x, v) appended
    std::vector<Mat2>* section_Phi = nullptr;   // optional: Phi at each section appended
    const std::atomic<bool>* cancel = nullptr;   // optional: when set, advance() returns after the piece
    // Local-error target of one Magnus substep on the scaled propagator (x / 1 cm, v / 0.1 m/s) inside a
    // compliant contact: 1e-11 for monodromies; a Lyapunov exponent at rtol 1e-8 needs less (step_tol_for).
    double step_tol = 1e-11;
    bool stop() const override { return cancel && cancel->load(std::memory_order_relaxed); }

    void on_piece(const Piece& piece) override;
    void on_section(const SectionPoint& sp) override;
    void on_impact(const ImpactEvent& ev) override;
    void on_regime(double t, Regime from, Regime to) override;
    // defer: the pieces' propagators are computed by finish(), on all cores, rather than as the Simulator
    // hands the pieces over; Phi and section_Phi are complete only after finish().
    bool defer = false;
    void finish();

private:
    // The propagators of one free-flight piece's substeps, in time order, into out (a compliant contact
    // piece's whole, made consistent with the flow): Phi = S Phi for each. They do not depend on Phi.
    void propagator(const Piece& piece, std::vector<Mat2>& out) const;
    void propagate(const Piece& piece, double a, double b, std::vector<Mat2>& P) const;
    void propagate_across_zero(const Piece& piece, double a, double b, std::vector<Mat2>& P) const;
    // Phi = M Phi, now or, deferred, in its turn.
    void apply(const Mat2& M) {
        if (!tape_.empty()) tape_.push_back({Op::Matrix, M, 0});
        else Phi = M * Phi;
    }
    Mat2 flow_consistent(const Piece& piece, const Vec2& y0, const Vec2& y1, const Mat2& P) const;
    void apply_impact_saltation(double t_hit, double v_minus, double t_release, double v_plus);

    const Params& p_;
    const Drive& d_;
    bool tangent_;
    bool inside_ = false;                 // compliant: the last piece ended in contact
    double t_hit_ = 0, v_minus_ = 0, v_plus_ = 0;   // the impact whose sticking is in progress
    // Deferred: what acts on Phi, in time order, and the pieces with their steps copied.
    struct Op {
        enum Kind { Matrix, Piece, Section } kind;
        Mat2 M;
        std::size_t index;
    };
    struct SavedPiece {
        ::impactlab::Piece piece;
        DenseStep step;
    };
    std::vector<Op> tape_;
    std::vector<SavedPiece> pieces_;
    std::vector<Mat2> substeps_;   // not deferred: one piece's, reused
};

// poincare_map, with Phi at each of the k sections appended to section_Phi where given (the monodromy of the
// first i periods: a corrector that shoots period by period takes its first guesses from them). defer: the
// tangent computed after the run on all cores (the same numbers as while it runs, which false gives).
MapResult period_map(const Params& p, double omega, const Vec2& y0, int k, bool tangent, const Tolerances& tol,
                     std::vector<Mat2>* section_Phi, bool defer = true);

}  // namespace impactlab::analysis::detail
