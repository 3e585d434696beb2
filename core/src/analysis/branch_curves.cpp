// Continued branches as the curves a bifurcation diagram draws (the CLI's PNG and the GUI's overlay alike).
#include <algorithm>

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

}  // namespace impactlab::analysis
