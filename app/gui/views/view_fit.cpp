#include "view_fit.hpp"

#include <algorithm>

namespace impactlab::gui {

AxisFit fit_axis(double lo, double hi, double min_span, double px, double margin_lo, double margin_hi) {
    if (!(hi - lo >= min_span)) {
        const double c = 0.5 * (lo + hi);
        lo = c - 0.5 * min_span;
        hi = c + 0.5 * min_span;
    }
    // A plot too small for its margins still gives the data a third of its length: the margins shrink.
    if (const double m = margin_lo + margin_hi; m > 2.0 * px / 3.0 && m > 0) {
        margin_lo *= 2.0 * px / 3.0 / m;
        margin_hi *= 2.0 * px / 3.0 / m;
    }
    const double per_px = (hi - lo) / std::max(px - margin_lo - margin_hi, 1.0);
    return {lo - margin_lo * per_px, hi + margin_hi * per_px};
}

AxisFit zoom_axis(AxisFit r, double anchor, double factor) {
    return {anchor + (r.lo - anchor) * factor, anchor + (r.hi - anchor) * factor};
}

AxisFit pan_axis(AxisFit r, double pixels, double px) {
    const double d = pixels * (r.hi - r.lo) / std::max(px, 1.0);
    return {r.lo - d, r.hi - d};
}

AxisFit potential_y_range(double v_min, double e_max, double px, double label_px) {
    const double lo = 1.18 * v_min;
    const double top = std::max(-2.3 * v_min, e_max);
    return fit_axis(lo, top, 0.0, px, 0.0, label_px);
}

}  // namespace impactlab::gui
