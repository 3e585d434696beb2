// Bounded nonlinear least squares on Ceres (Debian's libceres-dev): the fits of impactlab fit hand it a
// residual function over a few named knobs. The Jacobian is taken by forward differences with each knob's
// own step (a step that would leave the knob's bounds is taken downwards), since the residuals come from
// smoothers and simulations that have no analytic derivatives.
#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "identify/internal.hpp"
#include "parallel.hpp"

namespace impactlab::identify::detail {

namespace {

// Huber's loss on one residual, written as a residual of its own: sign(r) sqrt(rho(r^2)) squares to
// rho(r^2) = r^2 within delta, 2 delta |r| - delta^2 beyond. Summed over the samples that is the robust cost
// itself, so plain least squares on these residuals minimises it sample by sample. (A Ceres LossFunction
// would act on the whole block's summed square here: the residual function returns every sample at once.)
double huber_residual(double r, double delta) {
    const double a = std::abs(r);
    return a <= delta ? r : std::copysign(std::sqrt(delta * (2.0 * a - delta)), r);
}

class KnobCost : public ceres::CostFunction {
public:
    // Ceres works on z = value / scale and on R / r_scale, so that its tolerances (the gradient's is absolute)
    // mean the same in any units of the record: a cubic in strain has a gradient of 1e-20 in its own units.
    KnobCost(std::vector<Knob>& knobs, const ResidualFn& eval, const StepFn& step_of, int m, double huber_delta,
             std::vector<double> scale, double r_scale)
        : knobs_(knobs), eval_(eval), step_of_(step_of), huber_(huber_delta), scale_(std::move(scale)), r_scale_(r_scale),
          x_(knobs.size()) {
        set_num_residuals(m);
        mutable_parameter_block_sizes()->push_back(static_cast<int>(knobs.size()));
    }

    bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
        const double* z = parameters[0];
        const auto p = knobs_.size();
        // The budget is checked between iterations (the callback below): a failed evaluation would make Ceres
        // log an error to the user's terminal, and an iteration costs at most knobs + 2 evaluations.
        ++evaluations_;
        std::vector<double>& x = x_;
        for (std::size_t k = 0; k < p; ++k) *knobs_[k].value = x[k] = z[k] * scale_[k];
        if (!(eval_(R_) < INFINITY) || R_.size() != num_residuals()) return false;
        robust(R_);
        Eigen::Map<Eigen::VectorXd>(residuals, num_residuals()) = R_ / r_scale_;
        if (jacobians && jacobians[0]) {
            // Row-major num_residuals x p, as Ceres wants it.
            Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> J(jacobians[0], num_residuals(),
                                                                                                 static_cast<Eigen::Index>(p));
            evaluations_ += static_cast<long>(p);
            if (eval_at_) return parallel_columns(J);
            for (std::size_t k = 0; k < p; ++k) {
                const double h = step_of_(knobs_[k], x[k]);
                *knobs_[k].value = x[k] + h;
                const bool ok = eval_(Rt_) < INFINITY && Rt_.size() == num_residuals();
                *knobs_[k].value = x[k];
                if (!ok) return false;
                robust(Rt_);
                J.col(static_cast<Eigen::Index>(k)) = (Rt_ - R_) * (scale_[k] / (h * r_scale_));
            }
        }
        return true;
    }
    // 0: the plain residuals (the Jacobian handed back to the caller is of those).
    void set_huber(double delta) { huber_ = delta; }
    // The budget: at most `evaluations` residual evaluations and `seconds` of wall clock (0: none). The count
    // is what bounds a fit on any machine; the clock only stops one whose every evaluation has become slow.
    void set_budget(long evaluations, double seconds) {
        max_evaluations_ = evaluations;
        max_seconds_ = seconds;
        start_ = std::chrono::steady_clock::now();
    }
    bool exhausted() const {
        if (max_evaluations_ > 0 && evaluations_ >= max_evaluations_) return true;
        return max_seconds_ > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count() > max_seconds_;
    }
    long evaluations() const { return evaluations_; }

    void set_eval_at(const std::function<bool(const std::vector<double>&, Eigen::VectorXd&)>& f) { eval_at_ = f; }

private:
    // The forward differences of every knob at once, each at the point the sequential loop would take.
    template <class Jac>
    bool parallel_columns(Jac& J) const {
        const std::size_t p = knobs_.size();
        std::vector<double> h(p);
        for (std::size_t k = 0; k < p; ++k) h[k] = step_of_(knobs_[k], x_[k]);
        std::vector<Eigen::VectorXd> Rt(p);
        std::vector<char> ok(p, 0);
        ::impactlab::detail::for_each_index(p, [&](std::size_t k) {
            std::vector<double> at = x_;
            at[k] += h[k];
            ok[k] = eval_at_(at, Rt[k]) && Rt[k].size() == num_residuals();
        });
        for (std::size_t k = 0; k < p; ++k) {
            if (!ok[k]) return false;
            robust(Rt[k]);
            J.col(static_cast<Eigen::Index>(k)) = (Rt[k] - R_) * (scale_[k] / (h[k] * r_scale_));
        }
        return true;
    }
    void robust(Eigen::VectorXd& r) const {
        if (huber_ > 0)
            for (Eigen::Index i = 0; i < r.size(); ++i) r[i] = huber_residual(r[i], huber_);
    }

    std::vector<Knob>& knobs_;
    const ResidualFn& eval_;
    const StepFn& step_of_;
    double huber_;
    std::vector<double> scale_;
    double r_scale_;
    mutable std::vector<double> x_;   // the knobs' values at the point evaluated
    mutable long evaluations_ = 0;
    long max_evaluations_ = 0;
    double max_seconds_ = 0;
    std::chrono::steady_clock::time_point start_;
    mutable Eigen::VectorXd R_, Rt_;
    std::function<bool(const std::vector<double>&, Eigen::VectorXd&)> eval_at_;
};

// Ends the solve, keeping its best point, once the cost function's budget is spent.
class BudgetCallback : public ceres::IterationCallback {
public:
    explicit BudgetCallback(const KnobCost& cost) : cost_(cost) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary&) override {
        return cost_.exhausted() ? ceres::SOLVER_TERMINATE_SUCCESSFULLY : ceres::SOLVER_CONTINUE;
    }

private:
    const KnobCost& cost_;
};

}  // namespace

LsqSummary least_squares(std::vector<Knob>& knobs, const ResidualFn& eval, const StepFn& step_of, const LsqOptions& o,
                         Eigen::VectorXd& R, Eigen::MatrixXd* J) {
    LsqSummary out;
    const double ss0 = eval(R);
    out.initial_cost = ss0;
    out.final_cost = ss0;
    if (knobs.empty() || !(ss0 < INFINITY) || R.size() == 0) {
        if (J) J->resize(R.size(), static_cast<Eigen::Index>(knobs.size()));
        return out;
    }
    std::vector<double> x(knobs.size()), scale(knobs.size());
    for (std::size_t k = 0; k < knobs.size(); ++k) {
        const double v = std::clamp(*knobs[k].value, knobs[k].lo, knobs[k].hi);
        // A knob's scale: its value, or ten thousand of its steps where it starts near zero.
        scale[k] = std::max(std::abs(v), 1e4 * std::abs(knobs[k].step));
        if (!(scale[k] > 0) || !std::isfinite(scale[k])) scale[k] = 1.0;
        x[k] = v / scale[k];
    }
    const double r_rms = std::sqrt(ss0 / static_cast<double>(R.size())), r_scale = r_rms > 0 ? r_rms : 1.0;
    ceres::Problem::Options po;
    po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
    po.loss_function_ownership = ceres::TAKE_OWNERSHIP;
    ceres::Problem problem(po);
    auto* cost = new KnobCost(knobs, eval, step_of, static_cast<int>(R.size()), o.huber_delta, scale, r_scale);
    cost->set_eval_at(o.eval_at);
    problem.AddResidualBlock(cost, nullptr, x.data());
    for (std::size_t k = 0; k < knobs.size(); ++k) {
        if (knobs[k].lo > -1e11) problem.SetParameterLowerBound(x.data(), static_cast<int>(k), knobs[k].lo / scale[k]);
        if (knobs[k].hi < 1e11) problem.SetParameterUpperBound(x.data(), static_cast<int>(k), knobs[k].hi / scale[k]);
    }
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
    so.max_num_iterations = o.max_iterations;
    so.function_tolerance = o.function_tolerance;
    so.parameter_tolerance = 1e-10;
    so.gradient_tolerance = 1e-14;
    so.num_threads = 1;   // results must not depend on the machine; the residuals are cheap to split anyway
    so.logging_type = ceres::SILENT;
    so.minimizer_progress_to_stdout = false;
    // Every solve has a budget: by default what its iterations need with every step retried once (a Jacobian
    // and two trial points per iteration), so a fit ends on any record, however its model behaves; the solve
    // stops at the first iteration's end past it.
    const long p = static_cast<long>(knobs.size());
    cost->set_budget(o.max_evaluations > 0 ? o.max_evaluations : 2L * (p + 2) * std::max(1, o.max_iterations), o.max_seconds);
    BudgetCallback budget(*cost);
    so.callbacks.push_back(&budget);
    so.update_state_every_iteration = true;
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    out.iterations = static_cast<int>(summary.iterations.size());
    out.converged = summary.termination_type == ceres::CONVERGENCE;
    out.budget_spent = cost->exhausted();
    // The knobs at the best point Ceres accepted (the parameter block holds it, budget or not).
    cost->set_budget(0, 0);
    for (std::size_t k = 0; k < knobs.size(); ++k) *knobs[k].value = x[k] * scale[k];
    out.final_cost = eval(R);
    if (J) {
        cost->set_huber(0.0);
        const double* block[] = {x.data()};
        Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> Jr(R.size(), static_cast<Eigen::Index>(knobs.size()));
        double* jac[] = {Jr.data()};
        Eigen::VectorXd tmp(R.size());
        if (cost->Evaluate(block, tmp.data(), jac)) {
            // Back to dR/dknob in the knobs' and the residual's own units.
            *J = Jr;
            for (std::size_t k = 0; k < knobs.size(); ++k) J->col(static_cast<Eigen::Index>(k)) *= r_scale / scale[k];
        } else {
            J->setZero(R.size(), static_cast<Eigen::Index>(knobs.size()));
        }
        for (std::size_t k = 0; k < knobs.size(); ++k) *knobs[k].value = x[k] * scale[k];
        eval(R);
    }
    return out;
}

}  // namespace impactlab::identify::detail
