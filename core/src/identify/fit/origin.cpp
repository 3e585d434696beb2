// Stage 0: where the placeholder's spring is centred. "duffing" is symmetric about its origin; a record whose
// range lies far from its own zero (a tape read at 500 mm) cannot say the spring is symmetric about that zero
// unless its own well shows the even term such a spring has there, and a cubic about the zero would put a
// phantom well the mirror image away. Such a record's spring is centred on the record, its centre x0 fitted
// with the base parameters (an origin of coordinates, not a sensor fault).
#include "identify/fit/session.hpp"

namespace impactlab::identify::detail {

bool centre_placeholder(const MeasuredData& data, Model& model0, const FitOptions& o, FitReport& rep) {
    if (!model0.placeholder || !o.fit_baseline || centred_placeholder(model0)) return false;
    std::vector<double> xs;
    xs.reserve(data.x.size());
    for (double x : data.x)
        if (std::isfinite(x)) xs.push_back(x);
    if (xs.size() < 16) return false;
    const double lo = quantile(xs, 0.005), hi = quantile(xs, 0.995), extent = hi - lo;
    const double gap = lo > 0 ? lo : (hi < 0 ? -hi : 0.0);
    // Within one extent of the record its zero may well be the spring's centre: the origin is kept.
    if (!(extent > 0) || !(gap > extent)) return false;
    // A symmetric spring about the zero has, at a well x_w, the local even term 1.5 omega^2 / x_w: a run whose
    // own law shows that term out of its noise says the zero is the spring's centre (an intra-well record of a
    // double-well rig whose sensor reads 0 at the hilltop), and the origin is kept.
    std::vector<std::string> notes;
    Prep pr = prepare(data, model0, o, notes);
    pr.predictability = data_horizon(pr);
    const std::vector<RunWell> wells = data_wells(pr, hac_lag_of(pr));
    bool symmetric_about_zero = !wells.empty();
    for (const RunWell& w : wells) {
        const double k2_sym = 1.5 * w.omega * w.omega / w.x0, s_sym = std::abs(3.0 * w.omega * w.somega / w.x0);
        const bool shown = std::abs(w.k2) > 3.0 * w.sk2;
        const bool agrees = std::abs(w.k2 - k2_sym) < 3.0 * std::hypot(w.sk2, s_sym);
        symmetric_about_zero = symmetric_about_zero && std::isfinite(k2_sym) && shown && agrees;
    }
    if (symmetric_about_zero) return false;
    const double x0 = quantile(xs, 0.5);
    apply_effect(model0, "sensor_offset", {{"o", x0}});
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "the record lies %.6g to %.6g, %.3g of its extents from its zero, and its own well's even term is not the "
                  "one a spring symmetric about that zero would have there: the placeholder's spring is centred on the record (x0, its origin in the record's "
                  "coordinates, starts at the median %.6g and is fitted with the base parameters)",
                  lo, hi, gap / extent, x0);
    rep.notes.push_back(buf);
    return true;
}

}  // namespace impactlab::identify::detail
