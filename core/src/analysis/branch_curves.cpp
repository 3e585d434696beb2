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
            // Or, where that switch was not followed because a branch already through the doubling (a loop
            // reaching it from its other end) covers it, that branch.
            const Branch* child = nullptr;
            const double near = 1e-3 * std::max(1.0, std::abs(cur->param));
            for (const Branch& b : r.branches)
                if (b.parent == cur->branch && b.period == 2 * cur->period && !b.points.empty() &&
                    std::abs(b.points.front().param - cur->param) < near)
                    child = &b;
            for (const Branch& b : r.branches)
                if (!child && b.period == 2 * cur->period)
                    for (const BranchPoint& pt : b.points)
                        if (std::abs(pt.param - cur->param) < 0.25 * std::max(1.0, std::abs(cur->param)) * 0.04)
                            for (const Vec2& sp : pt.sections)
                                if (scaled_norm(sp - cur->y) < 0.05) child = &b;
            if (!child) break;
            // Its own doubling nearest the switch.
            const BifPoint* next = nullptr;
            for (const BifPoint& q : r.points)
                if (q.kind == BifKind::PeriodDoubling && q.branch == child->id && q.period == child->period &&
                    (!next || std::abs(q.param - cur->param) < std::abs(next->param - cur->param)))
                    next = &q;
            if (!next) break;
            // A cascade runs one way in the parameter: a doubling back the other way starts another chain.
            if (c.doublings.size() >= 2 && (next->param - cur->param) * (cur->param - c.doublings[c.doublings.size() - 2]->param) < 0)
                break;
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
