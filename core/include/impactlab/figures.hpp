// The paper's figures as data and as PNGs: shared by the CLI, the tests and the README's pictures.
#pragma once

#include <string>
#include <vector>

#include "impactlab/plot.hpp"
#include "impactlab/sweep.hpp"

namespace impactlab {

// The panels of Fig. 3: the EF forcing, A1C-EF, then the CF diagrams of A1C, A1C1, A3C, A1G, A1H.
struct Figure3Data {
    Diagram ef;                        // A1C under the EF ramp
    std::vector<Diagram> cf;           // A1C, A1C1, A3C, A1G, A1H, CF up
    EfSpec ef_spec;
};
// Runs the six jobs on up to hardware_concurrency threads; progress is the mean of the jobs'.
Figure3Data compute_figure3(int cf_steps, const Tolerances& tol, Progress* progress);

plot::Panel diagram_panel(const Diagram& d, const std::string& title);
void save_diagram_png(const Diagram& d, const std::string& path);
void save_figure3_png(const Figure3Data& f, const std::string& path);

}  // namespace impactlab
