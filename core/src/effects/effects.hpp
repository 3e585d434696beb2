// The extra physical effects, each defined whole (force law, fit hint, description) in its own file in this
// folder and listed once in registry.cpp. Sign convention: the force acts on the cart, positive towards +x,
// so it is exactly what the residual r = m x'' + F_R + F_SA + F_I - forcing measures.
#pragma once
#include "impactlab/params.hpp"

namespace impactlab::effects {
const EffectLaw& constant_force_law();
const EffectLaw& quadratic_damping_law();
const EffectLaw& tangential_unbalance_law();
const EffectLaw& magnet_offset_law();
const EffectLaw& magnet_drift_law();
const EffectLaw& damping_drift_law();
const EffectLaw& friction_drift_law();
const EffectLaw& stiffness_drift_law();
const EffectLaw& unbalance_drift_law();
const EffectLaw& even_stiffness_law();
const EffectLaw& cubic_stiffness_law();
const EffectLaw& linear_stiffness_law();
const EffectLaw& viscous_damping_law();
const EffectLaw& coulomb_friction_law();
const EffectLaw& stribeck_friction_law();
const EffectLaw& end_stop_law();
const EffectLaw& phase_offset_law();
const EffectLaw& unbalance_scale_law();
const EffectLaw& sensor_offset_law();
const EffectLaw& sensor_gain_law();
const EffectLaw& sensor_curvature_law();
const EffectLaw& sensor_delay_law();
const EffectLaw& unexplained_x_law();
const EffectLaw& unexplained_v_law();
const EffectLaw& unexplained_x_signv_law();
const EffectLaw& unexplained_x_v_law();
const EffectLaw& unexplained_phi_law();
const EffectLaw& unexplained_x_local_law();
const EffectLaw& unexplained_v_local_law();
const EffectLaw& unexplained_x_cycle_law();

// A law added to the registry for this object's lifetime, after the table's own. The test that adding an
// effect is one file plus one registry line adds one this way; no simulation or fit may run meanwhile on
// another thread, and they must be made and destroyed in reverse order.
class ScopedEffectLaw {
public:
    explicit ScopedEffectLaw(const EffectLaw& law);
    ~ScopedEffectLaw();
    ScopedEffectLaw(const ScopedEffectLaw&) = delete;
    ScopedEffectLaw& operator=(const ScopedEffectLaw&) = delete;
};
}  // namespace impactlab::effects
