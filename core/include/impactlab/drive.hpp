// How the rig is driven: the prescribed rotation of the unbalance (omega(t) piecewise linear through knots,
// phi its exact integral), and optionally a sampled input u(t) (a measured force or voltage, linear between
// samples) that acts on the cart as Params::input_gain * u. Constant omega (CF), the EF ramp, the synthetic
// data's plateaus and a measured record's input are all Drives; the simulator stops at every knot and
// every input sample, where the forcing's slope jumps.
#pragma once

#include <memory>
#include <numbers>
#include <vector>

namespace impactlab {

// One revolution of the unbalance [rad]: the Poincare sections sit at phi = phi0 + 2 pi i (phi0 = 0 unless
// Simulator::set_section_phase says otherwise).
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

class Drive {
public:
    Drive() : Drive(0.0) {}
    // Constant omega [rad/s] from time t0 with phase phi0 there.
    explicit Drive(double omega, double t0 = 0.0, double phi0 = 0.0);
    // omega through the knots (t_k [s], omega_k [rad/s]), constant before the first and after the last.
    static Drive piecewise_linear(const std::vector<double>& t, const std::vector<double>& omega, double phi0 = 0.0);
    // The paper's EF protocol: omega = 25.1 t / 2800 for 0 <= t <= 2800 s (scaled by omega_max, t_ramp).
    static Drive ef_ramp(double omega_max = 25.1, double t_ramp = 2800.0);

    double omega(double t) const { return omega_in(segment(t), t); }
    double alpha(double t) const { return alpha_in(segment(t), t); }   // phi'' [rad/s^2]
    double phi(double t) const { return phi_in(segment(t), t); }
    // All three at once, from one search of the knots (the equation of motion needs them at every stage).
    struct At { double phi, omega, alpha; };
    At at(double t) const {
        const std::size_t i = segment(t);
        return {phi_in(i, t), omega_in(i, t), alpha_in(i, t)};
    }
    // The time at which phi reaches `phase` (phi is nondecreasing); +inf if it never does.
    double time_of_phase(double phase) const;
    // Time of the next knot strictly after t (the forcing's slope jumps there), +inf if none.
    double next_knot(double t) const;
    double t_begin() const { return t_.front(); }

    // A sampled input u_k at t0 + k dt (k = 0..n-1), linear in between, held at its end values outside.
    // Throws std::invalid_argument for dt <= 0, fewer than two samples or a value that is not finite.
    void set_input(double t0, double dt, std::vector<double> u);
    bool has_input() const { return input_ != nullptr; }
    double input(double t) const;        // u(t); 0 without an input
    double input_rate(double t) const;   // du/dt

private:
    std::size_t segment(double t) const;
    double omega_in(std::size_t i, double t) const;   // within segment i = segment(t)
    double alpha_in(std::size_t i, double t) const;
    double phi_in(std::size_t i, double t) const;
    std::vector<double> t_, w_, phi_;   // knots and phi at each knot
    // Shared, so that copying a Drive (one per worker, one per window) never copies a long record.
    struct Input { double t0, dt; std::vector<double> u; };
    std::shared_ptr<const Input> input_;
};

}  // namespace impactlab
