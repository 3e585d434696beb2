// The grazing monitor: how close the orbit comes to the bumper, period by period, so that a
// grazing bifurcation can be seen coming: the distance xI - max x over the last forcing period goes to 0
// from a clear orbit, the impact velocity goes to 0 from an impacting one. Fed with the core simulator's
// pieces and events (exact dense output, not the display samples, which miss a 0.1 ms contact of C1) on the
// thread that runs the simulation; GL-free.
#pragma once

#include <cmath>
#include <limits>

#include "impactlab/simulator.hpp"

namespace impactlab::gui {

class GrazingMonitor {
public:
    // One forcing period, from one section phi = 2 pi n to the next.
    struct Period {
        double t = 0;                  // the section that closed it [s]
        double x_max = 0;              // the largest x over the period [m]
        double distance = 0;           // xI - x_max [m]: > 0 clear of the bumper, <= 0 touching or pressing it
        double v_impact = std::numeric_limits<double>::quiet_NaN();   // the last impact's v- (rigid) or the last
                                       // contact's entry velocity (compliant) in the period [m/s]; NaN: none
        double penetration = 0;        // compliant: the deepest x - xI in the period [m]; rigid: 0
        int impacts = 0;               // impacts (rigid) or contacts begun (compliant) in the period
    };

    // Forget everything: the next section only opens a period (the first one would be partial).
    void reset();
    // The simulator's observer calls, in time order. xI: the bumper now [m]; compliant: a Hunt-Crossley law.
    void on_piece(const Piece& piece, double xI, bool compliant);
    void on_impact(const ImpactEvent& ev);
    // Closes the period at this section. Returns true (and fills `out`) when a whole period lies behind it.
    bool on_section(double t, double xI, Period& out);

private:
    void open();
    bool started_ = false;        // a section has opened the current period
    double x_max_ = -std::numeric_limits<double>::infinity();
    double v_impact_ = std::numeric_limits<double>::quiet_NaN();
    double penetration_ = 0;
    int impacts_ = 0;
    bool in_contact_ = false;     // compliant: the last piece ended inside the bumper
};

}  // namespace impactlab::gui
