// Continued branches as the curves a bifurcation diagram draws (the CLI's PNG and the GUI's overlay alike).
#include <algorithm>
#include <cmath>

#include "impactlab/analysis.hpp"

namespace impactlab::analysis {

std::vector<BranchCurve> branch_curves(const ContinuationResult& r) {
    std::vector<BranchCurve> out;
    for (const Branch& b : r.branches) {
        const int k = std::max(b.period, 1);
        std::vector<BranchCurve> curves(static_cast<std::size_t>(k));
        for (BranchCurve& c : curves) {
            c.branch = b.id;
            c.period = k;
        }
        for (const BranchPoint& q : b.points) {
            for (std::size_t i = 0; i < curves.size() && i < q.sections.size(); ++i) {
                curves[i].param.push_back(q.param);
                curves[i].x.push_back(q.sections[i][0]);
                curves[i].stable.push_back(q.stable ? 1 : 0);
            }
        }
        for (BranchCurve& c : curves)
            if (!c.param.empty()) out.push_back(std::move(c));
    }
    return out;
}

Cascade find_cascade(const ContinuationResult& r) {
    Cascade best;
    for (const BifPoint& d0 : r.points) {
        if (d0.kind != BifKind::PeriodDoubling) continue;
        Cascade c;
        c.doublings.push_back(&d0);
        for (const BifPoint* cur = &d0;;) {
            // The branch switched onto at cur: a child of cur's branch, of twice its period, starting there.
            const Branch* child = nullptr;
            for (const Branch& b : r.branches)
                if (b.parent == cur->branch && b.period == 2 * cur->period && !b.points.empty() &&
                    std::abs(b.points.front().param - cur->param) < 1e-3 * std::max(1.0, std::abs(cur->param)))
                    child = &b;
            if (!child) break;
            // Its own doubling nearest the switch.
            const BifPoint* next = nullptr;
            for (const BifPoint& q : r.points)
                if (q.kind == BifKind::PeriodDoubling && q.branch == child->id && q.period == child->period &&
                    (!next || std::abs(q.param - cur->param) < std::abs(next->param - cur->param)))
                    next = &q;
            if (!next) break;
            c.doublings.push_back(next);
            cur = next;
        }
        if (c.doublings.size() > best.doublings.size()) best = c;
    }
    for (std::size_t j = 1; j + 1 < best.doublings.size(); ++j)
        best.ratios.push_back((best.doublings[j]->param - best.doublings[j - 1]->param) /
                              (best.doublings[j + 1]->param - best.doublings[j]->param));
    return best;
}

}  // namespace impactlab::analysis
