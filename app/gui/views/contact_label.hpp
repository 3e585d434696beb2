// The one sentence the rig's badge and the status bar both show for the cart's contact with the bumper,
// from the same sample, so the two can never disagree (the rig saying "on the compliant bumper" while the
// status bar says free flight). A compliant law has no regimes II and III: pressing it is regime I with F_I > 0.
// GL-free.
#pragma once

#include "impactlab/params.hpp"
#include "impactlab/simulator.hpp"

namespace impactlab::gui {

inline const char* contact_label(const Params& p, Regime regime, double bumper_force) {
    switch (regime) {
        case Regime::Sticking: return "II  sticking (impact)";
        case Regime::Contact: return "III  permanent contact";
        case Regime::Free: break;
    }
    return p.has_bumper() && !p.rigid() && bumper_force > 0 ? "I  on the compliant bumper" : "I  free flight";
}

// True when the cart touches the bumper: held (II, III) or pressing a compliant one.
inline bool in_contact(const Params& p, Regime regime, double bumper_force) {
    return regime != Regime::Free || (p.has_bumper() && bumper_force > 0);
}

}  // namespace impactlab::gui
