// The effect registry: one line per named physical effect. A new effect is one file (its force law, how fit
// looks for it, how it is described) plus one line here. (impactlab fit also knows four effects that change
// the base model rather than add a force: bumper_offset, impact_duration, restitution and cart_mass, each a
// row of core/src/identify/base_effects.cpp.)
#include <stdexcept>

#include "effects/effects.hpp"

namespace impactlab {

namespace {

// Room for a few scoped additions without moving the table: models hold pointers into it.
constexpr std::size_t kSpare = 8;

std::vector<EffectLaw>& table() {
    static std::vector<EffectLaw> laws = [] {
        std::vector<EffectLaw> t{
            effects::constant_force_law(),
            effects::quadratic_damping_law(),
            effects::tangential_unbalance_law(),
            effects::magnet_offset_law(),
            effects::magnet_drift_law(),
            effects::damping_drift_law(),
            effects::friction_drift_law(),
            effects::stiffness_drift_law(),
            effects::unbalance_drift_law(),
            effects::even_stiffness_law(),
            effects::cubic_stiffness_law(),
            effects::linear_stiffness_law(),
            effects::viscous_damping_law(),
            effects::coulomb_friction_law(),
            effects::stribeck_friction_law(),
            effects::end_stop_law(),
            effects::phase_offset_law(),
            effects::unbalance_scale_law(),
            effects::sensor_offset_law(),
            effects::sensor_gain_law(),
            effects::sensor_curvature_law(),
            effects::sensor_delay_law(),
            effects::unexplained_x_law(),
            effects::unexplained_v_law(),
            effects::unexplained_x_signv_law(),
            effects::unexplained_x_v_law(),
            effects::unexplained_phi_law(),
            effects::unexplained_x_local_law(),
            effects::unexplained_v_local_law(),
            effects::unexplained_x_cycle_law(),
        };
        t.reserve(t.size() + kSpare);
        return t;
    }();
    return laws;
}

}  // namespace

const std::vector<EffectLaw>& effect_laws() { return table(); }

effects::ScopedEffectLaw::ScopedEffectLaw(const EffectLaw& law) {
    std::vector<EffectLaw>& t = table();
    if (t.size() == t.capacity()) throw std::logic_error("effect registry: no room for another scoped law");
    if (find_effect(law.id)) throw std::logic_error(std::string("effect registry: '") + law.id + "' is taken");
    t.push_back(law);
}

effects::ScopedEffectLaw::~ScopedEffectLaw() { table().pop_back(); }

}  // namespace impactlab
