// The effect registry: one line per named physical effect. A new effect is one file (its force law, how fit
// looks for it, how it is described) plus one line here. (impactlab fit also knows four effects that change
// the base model rather than add a force: bumper_offset, impact_duration, restitution and cart_mass, each a
// row of core/src/identify/base_effects.cpp.)
#include "effects/effects.hpp"

namespace impactlab {

const std::vector<EffectLaw>& effect_laws() {
    static const std::vector<EffectLaw> table{
        effects::constant_force_law(),
        effects::quadratic_damping_law(),
        effects::tangential_unbalance_law(),
        effects::magnet_offset_law(),
        effects::magnet_drift_law(),
        effects::even_stiffness_law(),
        effects::linear_stiffness_law(),
        effects::viscous_damping_law(),
        effects::coulomb_friction_law(),
        effects::stribeck_friction_law(),
        effects::phase_offset_law(),
        effects::unbalance_scale_law(),
        effects::sensor_offset_law(),
        effects::sensor_gain_law(),
        effects::sensor_delay_law(),
        effects::unexplained_x_law(),
        effects::unexplained_v_law(),
        effects::unexplained_x_signv_law(),
        effects::unexplained_phi_law(),
    };
    return table;
}

}  // namespace impactlab
