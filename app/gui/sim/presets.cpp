#include "presets.hpp"

namespace impactlab::gui {

// Every omega below was checked with
//   impactlab poincare --model M --omega W --periods 128 --transient 400 --x0 -0.011
// taking the smallest k after which every point recurs in x and v (20 um, 0.2 mm/s): 1, 2, none <= 16
// (chaos), and the window's period.
// A1: period 1 up to ~10.9, period 2 from ~11 to ~12.9, chaos ~13..19.4, then an inverse cascade
//     (period 4 at 19.5, period 2 from 20, period 1 from 22.25). A1G and A1C1 have the paper's wide
//     window (period 1, the cart far left, ~14.25..14.75 / 14.25..15.0); A1H and A1C only narrow period-3
//     windows (16.40..16.45 and 16.50..16.55).
// A3: period 1 up to ~10.5, period 2 from ~10.75 to ~12.75, chaos ~13..18.2, period 4 near 18.3, period 2
//     from 18.5; narrow windows: A3H period 6 at 15.35 (a doubled period 3:
//     three pairs 0.03-0.1 mm apart, which counting clusters in x alone had read as period 5), A3C period 3 at 15.5, A3G period 3 at 15.70,
//     A3C1 period 3 at 15.75.
std::vector<Preset> presets_for(const std::string& model) {
    const bool a3 = model.rfind("A3", 0) == 0;
    const std::string imp = model.size() > 2 ? model.substr(2) : "H";
    constexpr double x0 = -0.011;   // at rest in the left well
    std::vector<Preset> p;
    p.push_back({"Period 1", 9.0, x0, 1, "period 1: one Poincare point; the cart swings in the left well, clear of the bumper"});
    p.push_back({"Period 2", 12.0, x0, 2, "after the first period doubling: two Poincare points"});
    p.push_back({"Chaos", a3 ? 16.0 : 18.0, x0, 0,
                 "a strange attractor: the cart keeps hitting the bumper at the hilltop x = 0"});
    double w = 16.45;
    int period = 3;
    const char* note = "a narrow period-3 window inside the chaotic range";
    if (!a3) {
        if (imp == "G" || imp == "C1") {
            w = 14.5;
            period = 1;
            note = "the wide periodic window of A1G and A1C1 (the paper's Fig. 3): period 1 far in the left well";
        } else if (imp == "C") {
            w = 16.55;
        }
    } else {
        if (imp == "H") {
            w = 15.35;
            period = 6;
            note = "a narrow window inside the chaotic range: a period-3 orbit doubled to period 6 (three close pairs)";
        } else if (imp == "C") {
            w = 15.5;
        } else if (imp == "G") {
            w = 15.70;
        } else {
            w = 15.75;
        }
    }
    p.push_back({"Window", w, x0, period, note});
    return p;
}

}  // namespace impactlab::gui
