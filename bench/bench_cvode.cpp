// bench_cvode: the CF diagrams of A1C and A1H written with SUNDIALS CVODE 6 (BDF, dense direct linear solver
// with the analytic Jacobian, root-finding for the events), timed against impactlab's run_cf_sweep.
//
// - Free flight (regime I): CVode in CV_NORMAL mode towards the next Poincare section, with CVodeSetStopTime
//   on it, so every section is hit exactly and the BDF history runs on through it; CVodeSetMaxStep(h_max),
//   impactlab's 0.5 s (without it CVODE steps over the bumper grazings of the creeping cart at small omega).
// - Events by CVodeRootInit on g = x - xI: rigid (A1H) only the approach from below (root direction +1): an
//   impact; compliant (A1C) contact starts or ends, a kink in the force: the root direction alternates (+1 while
//   clear of the bumper, -1 in contact).
// - Rigid regime II (sticking for T_imp(v-)) needs no integration: the cart is held; regime III integrates
//   y' = 0 with a root function on the normal force N(t) (direction -1) and a step cap of a 16th of a period
//   (two zeros of N in one step would cancel).
// - CVodeReInit after every discontinuity (impact, release, lift-off, contact kink) and at every new omega.
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "peer_common.hpp"

namespace {

class CvodeBackend {
public:
    CvodeBackend(peer::Model& model, double rtol, double atol_x, double atol_v, double h_max)
        : M_(model), h_max_(h_max) {
        check(SUNContext_Create(nullptr, &ctx_), "SUNContext_Create");
        y_ = N_VNew_Serial(2, ctx_);
        atol_ = N_VNew_Serial(2, ctx_);
        if (!y_ || !atol_) throw std::runtime_error("N_VNew_Serial failed");
        NV_Ith_S(y_, 0) = 0.0;
        NV_Ith_S(y_, 1) = 0.0;
        NV_Ith_S(atol_, 0) = atol_x;
        NV_Ith_S(atol_, 1) = atol_v;
        mem_ = CVodeCreate(CV_BDF, ctx_);
        if (!mem_) throw std::runtime_error("CVodeCreate failed");
        check(CVodeInit(mem_, &CvodeBackend::rhs, 0.0, y_), "CVodeInit");
        check(CVodeSVtolerances(mem_, rtol, atol_), "CVodeSVtolerances");
        check(CVodeSetUserData(mem_, this), "CVodeSetUserData");
        A_ = SUNDenseMatrix(2, 2, ctx_);
        LS_ = SUNLinSol_Dense(y_, A_, ctx_);
        if (!A_ || !LS_) throw std::runtime_error("dense matrix / linear solver creation failed");
        check(CVodeSetLinearSolver(mem_, LS_, A_), "CVodeSetLinearSolver");
        check(CVodeSetJacFn(mem_, &CvodeBackend::jac), "CVodeSetJacFn");
        check(CVodeRootInit(mem_, 1, &CvodeBackend::root), "CVodeRootInit");
        check(CVodeSetNoInactiveRootWarn(mem_), "CVodeSetNoInactiveRootWarn");
        check(CVodeSetMaxNumSteps(mem_, 100000000L), "CVodeSetMaxNumSteps");
    }
    ~CvodeBackend() {
        CVodeFree(&mem_);
        SUNLinSolFree(LS_);
        SUNMatDestroy(A_);
        N_VDestroy(atol_);
        N_VDestroy(y_);
        SUNContext_Free(&ctx_);
    }
    CvodeBackend(const CvodeBackend&) = delete;
    CvodeBackend& operator=(const CvodeBackend&) = delete;

    void restart_free(double t, double x, double v, int side) {
        contact_ = false;
        NV_Ith_S(y_, 0) = x;
        NV_Ith_S(y_, 1) = v;
        // Only the crossing that leaves the current side: g = x - xI falls when leaving the bumper, rises when
        // reaching it (always the case for a rigid one, side -1).
        reinit(t, side > 0 ? -1 : (side < 0 ? +1 : 0), h_max_);
    }
    void restart_contact(double t) {
        contact_ = true;
        NV_Ith_S(y_, 0) = M_.xI;
        NV_Ith_S(y_, 1) = 0.0;
        const double h = peer::kTwoPi / M_.omega / 16.0;
        reinit(t, -1, h_max_ > 0 ? std::min(h, h_max_) : h);
    }
    bool free_flight(double t_stop, double& t, double& x, double& v) {
        const bool root = advance(t_stop, t);
        x = NV_Ith_S(y_, 0);
        v = NV_Ith_S(y_, 1);
        return root;
    }
    bool contact(double t_stop, double& t) { return advance(t_stop, t); }
    std::uint64_t steps() const {
        long int n = 0;
        CVodeGetNumSteps(mem_, &n);
        return steps_before_ + static_cast<std::uint64_t>(n);
    }

private:
    static void check(int flag, const char* what) {
        if (flag < 0) throw std::runtime_error(std::string(what) + " failed with flag " + std::to_string(flag));
    }
    void reinit(double t, int direction, double h_max) {
        long int n = 0;
        CVodeGetNumSteps(mem_, &n);   // CVodeReInit zeroes the counters
        steps_before_ += static_cast<std::uint64_t>(n);
        check(CVodeReInit(mem_, t, y_), "CVodeReInit");
        int dir = direction;
        check(CVodeSetRootDirection(mem_, &dir), "CVodeSetRootDirection");
        check(CVodeSetMaxStep(mem_, h_max), "CVodeSetMaxStep");
    }
    // Integrates to t_stop exactly; returns true at a root (t = the root) before it.
    bool advance(double t_stop, double& t) {
        check(CVodeSetStopTime(mem_, t_stop), "CVodeSetStopTime");
        double tret = t;
        const int flag = CVode(mem_, t_stop, y_, &tret, CV_NORMAL);
        check(flag, "CVode");
        if (flag == CV_ROOT_RETURN) {
            t = tret;
            return true;
        }
        t = t_stop;
        return false;
    }

    static int rhs(double t, N_Vector y, N_Vector yd, void* ud) {
        const auto* self = static_cast<const CvodeBackend*>(ud);
        if (self->contact_) {
            NV_Ith_S(yd, 0) = 0.0;
            NV_Ith_S(yd, 1) = 0.0;
            return 0;
        }
        double dx, dv;
        self->M_.rhs(t, NV_Ith_S(y, 0), NV_Ith_S(y, 1), dx, dv);
        NV_Ith_S(yd, 0) = dx;
        NV_Ith_S(yd, 1) = dv;
        return 0;
    }
    static int jac(double t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* ud, N_Vector, N_Vector, N_Vector) {
        const auto* self = static_cast<const CvodeBackend*>(ud);
        double Jm[2][2] = {{0.0, 0.0}, {0.0, 0.0}}, dfdt[2];
        if (!self->contact_) self->M_.jacobian(t, NV_Ith_S(y, 0), NV_Ith_S(y, 1), Jm, dfdt);
        for (int i = 0; i < 2; ++i)
            for (int j = 0; j < 2; ++j) SM_ELEMENT_D(J, i, j) = Jm[i][j];
        return 0;
    }
    static int root(double t, N_Vector y, double* g, void* ud) {
        const auto* self = static_cast<const CvodeBackend*>(ud);
        g[0] = self->contact_ ? self->M_.normal_force(t) : NV_Ith_S(y, 0) - self->M_.xI;
        return 0;
    }

    peer::Model& M_;
    SUNContext ctx_ = nullptr;
    N_Vector y_ = nullptr, atol_ = nullptr;
    void* mem_ = nullptr;
    SUNMatrix A_ = nullptr;
    SUNLinearSolver LS_ = nullptr;
    double h_max_ = 0;
    bool contact_ = false;
    std::uint64_t steps_before_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
    // Default rtol: the loosest of 1e-6, 3e-7, 1e-7, 3e-8, ... at which the settled period-1 section points agree
    // with impactlab's to about 1e-6 m (every run measures and prints it; the numbers are in bench/README.md).
    constexpr double kDefaultRtol = 1e-7;
    const peer::Options o = peer::parse_options(argc, argv, "bench_cvode", kDefaultRtol);
    try {
        return peer::peer_main(o, "cvode", "SUNDIALS CVODE 6.4, BDF, dense linear solver, analytic Jacobian, "
                               "CVodeRootInit events, CVodeSetStopTime sections",
                               [](peer::Model& M, const peer::CfGrid& grid, const peer::Accuracy& acc) {
                                   CvodeBackend B(M, acc.rtol, acc.rtol * acc.scale_x, acc.rtol * acc.scale_v, acc.h_max);
                                   return peer::run_cf(M, B, grid);
                               });
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_cvode: %s\n", e.what());
        return 1;
    }
}
