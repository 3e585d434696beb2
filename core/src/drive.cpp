#include "impactlab/drive.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace impactlab {

Drive::Drive(double omega, double t0, double phi0) : t_{t0}, w_{omega}, phi_{phi0} {
    if (!std::isfinite(omega) || omega < 0) throw std::invalid_argument("omega must be finite and >= 0");
}

Drive Drive::piecewise_linear(const std::vector<double>& t, const std::vector<double>& omega, double phi0) {
    if (t.empty() || t.size() != omega.size())
        throw std::invalid_argument("omega profile: need as many times as omegas, at least one");
    Drive d(omega[0], t[0], phi0);
    for (std::size_t i = 1; i < t.size(); ++i) {
        if (!(t[i] > t[i - 1])) throw std::invalid_argument("omega profile: knot times must increase");
        if (!std::isfinite(omega[i]) || omega[i] < 0) throw std::invalid_argument("omega profile: omega must be >= 0");
        const double dt = t[i] - t[i - 1];
        d.t_.push_back(t[i]);
        d.w_.push_back(omega[i]);
        d.phi_.push_back(d.phi_.back() + 0.5 * (omega[i - 1] + omega[i]) * dt);
    }
    return d;
}

Drive Drive::ef_ramp(double omega_max, double t_ramp) {
    return piecewise_linear({0.0, t_ramp}, {0.0, omega_max});
}

std::size_t Drive::segment(double t) const {
    // Index of the last knot at or before t (0 if t precedes all knots).
    const auto it = std::upper_bound(t_.begin(), t_.end(), t);
    return it == t_.begin() ? 0 : static_cast<std::size_t>(it - t_.begin()) - 1;
}

double Drive::omega_in(std::size_t i, double t) const {
    if (i + 1 >= t_.size() || t <= t_[i]) return w_[i];
    return w_[i] + (w_[i + 1] - w_[i]) * (t - t_[i]) / (t_[i + 1] - t_[i]);
}

double Drive::alpha_in(std::size_t i, double t) const {
    if (i + 1 >= t_.size() || t < t_[i]) return 0.0;
    return (w_[i + 1] - w_[i]) / (t_[i + 1] - t_[i]);
}

double Drive::phi_in(std::size_t i, double t) const {
    const double tau = t - t_[i];
    if (i + 1 >= t_.size() || tau < 0) return phi_[i] + w_[i] * tau;
    const double a = (w_[i + 1] - w_[i]) / (t_[i + 1] - t_[i]);
    return phi_[i] + tau * (w_[i] + 0.5 * a * tau);
}

double Drive::time_of_phase(double phase) const {
    const double inf = std::numeric_limits<double>::infinity();
    if (phase <= phi_[0]) {
        if (phase == phi_[0]) return t_[0];
        return w_[0] > 0 ? t_[0] + (phase - phi_[0]) / w_[0] : -inf;
    }
    // The first knot with phi >= phase: the phase is reached exactly there, or inside the segment before.
    const std::size_t k = static_cast<std::size_t>(std::lower_bound(phi_.begin(), phi_.end(), phase) - phi_.begin());
    if (k < phi_.size() && phi_[k] == phase) {
        // phi may rest at this value (omega = 0 on a stretch): the first time it gets there.
        std::size_t first = k;
        while (first > 0 && phi_[first - 1] == phase) --first;
        return t_[first];
    }
    const std::size_t i = k - 1;
    const double dphi = phase - phi_[i];
    if (i + 1 >= t_.size()) return w_[i] > 0 ? t_[i] + dphi / w_[i] : inf;
    const double a = (w_[i + 1] - w_[i]) / (t_[i + 1] - t_[i]);
    // Solve 1/2 a tau^2 + w tau = dphi in the cancellation-free form.
    const double disc = std::max(0.0, w_[i] * w_[i] + 2.0 * a * dphi);
    const double denom = w_[i] + std::sqrt(disc);
    if (denom <= 0) return inf;
    return std::min(t_[i] + 2.0 * dphi / denom, t_[i + 1]);
}

double Drive::next_knot(double t) const {
    const auto it = std::upper_bound(t_.begin(), t_.end(), t);
    double next = it == t_.end() ? std::numeric_limits<double>::infinity() : *it;
    if (input_) {
        // The first input sample strictly after t (rounding may put t a hair before a sample it sits on).
        const Input& in = *input_;
        const double s = (t - in.t0) / in.dt;
        const double last = static_cast<double>(in.u.size() - 1);
        if (s < last) {
            double k = std::max(0.0, std::floor(s) + 1.0);
            double tk = in.t0 + k * in.dt;
            if (tk <= t) tk = in.t0 + (++k) * in.dt;
            if (k <= last) next = std::min(next, tk);
        }
    }
    return next;
}

void Drive::set_input(double t0, double dt, std::vector<double> u) {
    if (!std::isfinite(t0) || !(dt > 0) || !std::isfinite(dt)) throw std::invalid_argument("input: the sample step must be positive");
    if (u.size() < 2) throw std::invalid_argument("input: need at least two samples");
    for (std::size_t k = 0; k < u.size(); ++k)
        if (!std::isfinite(u[k])) throw std::invalid_argument("input: sample " + std::to_string(k) + " is not a finite number");
    input_ = std::make_shared<const Input>(Input{t0, dt, std::move(u)});
}

double Drive::input(double t) const {
    if (!input_) return 0.0;
    const Input& in = *input_;
    const double s = (t - in.t0) / in.dt;
    const double last = static_cast<double>(in.u.size() - 1);
    if (!(s > 0)) return in.u.front();
    if (s >= last) return in.u.back();
    const auto k = static_cast<std::size_t>(s);
    const double f = s - static_cast<double>(k);
    return in.u[k] + f * (in.u[k + 1] - in.u[k]);
}

double Drive::input_rate(double t) const {
    if (!input_) return 0.0;
    const Input& in = *input_;
    const double s = (t - in.t0) / in.dt;
    const double last = static_cast<double>(in.u.size() - 1);
    if (!(s >= 0) || s >= last) return 0.0;
    const auto k = static_cast<std::size_t>(s);
    return (in.u[k + 1] - in.u[k]) / in.dt;
}

}  // namespace impactlab
