#include "bifurcation_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "impactlab/drive.hpp"
#include "sim/sim_engine.hpp"   // kMaxOmega

namespace impactlab::gui {

namespace {

// The EF ramp's section points, published in chunks of this many (about 1.5 % of the ramp's 17,000).
constexpr std::size_t kEfChunk = 256;

// Watches the EF ramp's sections and publishes them (n >= 1, as run_ef_ramp keeps them, with omega(t)).
class RampPublisher : public Observer {
public:
    RampPublisher(Feed<DiagramPoint>& feed, const Drive& drive) : feed_(feed), drive_(drive) {}
    ~RampPublisher() override = default;
    void on_section(const SectionPoint& sp) override {
        if (sp.n < 1) return;
        chunk_.push_back({drive_.omega(sp.t), sp.x, sp.v});
        if (chunk_.size() >= kEfChunk) feed_.publish(chunk_, 0);
    }
    void flush() { feed_.publish(chunk_, 0); }

private:
    Feed<DiagramPoint>& feed_;
    Drive drive_;
    std::vector<DiagramPoint> chunk_;
};

// omega_j = lo + (hi - lo) j / steps, j = 1..steps, as the core's omega_min + (max - min) (j - 1)/(steps - 1).
void set_levels(CfSpec& s, double lo, double hi, int steps) {
    s.steps = steps;
    s.omega_max = hi;
    s.omega_min = lo + (hi - lo) / steps;
}

std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

}  // namespace

const char* bif_protocol_name(BifProtocol p) {
    switch (p) {
        case BifProtocol::CfUp: return "CF up";
        case BifProtocol::CfDown: return "CF down";
        case BifProtocol::Ef: return "EF ramp";
    }
    return "?";
}

CfSpec cf_spec(const BifRequest& r) {
    CfSpec spec;
    set_levels(spec, r.omega_lo, r.omega_hi, r.steps);
    spec.transient = r.transient;
    spec.record = r.record;
    spec.direction = r.protocol == BifProtocol::CfDown ? SweepDirection::Down : SweepDirection::Up;
    return spec;
}

EfSpec ef_spec(const BifRequest& r) {
    EfSpec spec;
    spec.omega_max = r.omega_hi;
    spec.t_ramp = r.omega_hi / r.ef_rate;   // the same rate whatever omega it ends at
    return spec;
}

CfSpec cf_spec(const LyapunovStripRequest& r) {
    CfSpec spec;
    set_levels(spec, r.omega_lo, r.omega_hi, r.steps);
    spec.transient = r.transient;
    spec.record = r.record;
    spec.direction = r.direction;
    return spec;
}

std::string check_omega_range(double lo, double hi) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return "ω range: not a number";
    if (lo < 0) return "ω min " + fmt(lo) + " rad/s is below 0";
    if (hi > kMaxOmega) return "ω max " + fmt(hi) + " rad/s is above " + fmt(kMaxOmega) + " rad/s";
    if (!(lo < hi)) return "ω min " + fmt(lo) + " must be below ω max " + fmt(hi) + " rad/s";
    return "";
}

SweepLimits sweep_limits(SweepParam over) {
    switch (over) {
        case SweepParam::Omega: return {0.0, kMaxOmega, kMinBoxSpan};
        case SweepParam::XI: return {-kRailHalfTravel, kRailHalfTravel, 1e-4};   // 0.1 mm
        case SweepParam::M0e: return {1e-4, 10.0, 1e-4};
    }
    return {0.0, kMaxOmega, kMinBoxSpan};
}

std::optional<BifRequest> box_request(const BifRequest& base, double w0, double w1) {
    if (!std::isfinite(w0) || !std::isfinite(w1)) return std::nullopt;
    const SweepLimits lim = sweep_limits(base.over);
    const double lo = std::clamp(std::min(w0, w1), lim.lo, lim.hi), hi = std::clamp(std::max(w0, w1), lim.lo, lim.hi);
    if (hi - lo < lim.min_box) return std::nullopt;
    BifRequest r = base;
    if (base.over == SweepParam::Omega) {
        r.omega_lo = lo;
        r.omega_hi = hi;
    } else {
        r.lo = lo;
        r.hi = hi;
    }
    return r;
}

ParamSweep param_sweep(const BifRequest& r) {
    if (r.over == SweepParam::Omega) {
        const CfSpec spec = cf_spec(r);
        return {SweepParam::Omega, spec.omega_min, spec.omega_max, spec.steps, spec.direction, 0.0};
    }
    return {r.over, r.lo, r.hi, r.steps, r.protocol == BifProtocol::CfDown ? SweepDirection::Down : SweepDirection::Up,
            r.omega};
}

std::pair<double, double> swept_range(const BifRequest& r) {
    if (r.over != SweepParam::Omega) return {r.lo, r.hi};
    return {r.protocol == BifProtocol::Ef ? 0.0 : r.omega_lo, r.omega_hi};
}

void BifurcationJob::start(const BifRequest& req) {
    job_.cancel();
    job_.wait();   // the old worker is gone before its feed is: nothing publishes into a dropped feed
    feed_ = std::make_shared<Feed<DiagramPoint>>();
    level_feed_ = std::make_shared<Feed<DiagramLevel>>();
    job_.start([req, feed = feed_, level_feed = level_feed_](Progress& prog) {
        if (req.protocol == BifProtocol::Ef) {
            const EfSpec spec = ef_spec(req);
            RampPublisher pub(*feed, Drive::ef_ramp(spec.omega_max, spec.t_ramp));
            Diagram d = run_ef_ramp(req.params, spec, &prog, {}, &pub);
            pub.flush();
            return d;
        }
        LevelPublisher pub(*feed, *level_feed);
        return run_cf_param_sweep(req.params, param_sweep(req), req.transient, req.record, &prog, {}, &pub, req.settle);
    });
}

void LyapunovStripJob::start(const LyapunovStripRequest& req) {
    job_.cancel();
    job_.wait();
    feed_ = std::make_shared<Feed<analysis::LyapunovPoint>>();
    job_.start([req, feed = feed_](Progress& prog) {
        int done = 0;
        std::vector<analysis::LyapunovPoint> one;
        return analysis::lyapunov_sweep(req.params, cf_spec(req), &prog, {}, [&](const analysis::LyapunovPoint& q) {
            one.assign(1, q);
            feed->publish(one, ++done);
        });
    });
}

}  // namespace impactlab::gui
