# Effect force laws, one file each (paths relative to core/). The table is src/effects/registry.cpp.
set(IMPACTLAB_EFFECT_SOURCES
  src/effects/constant_force.cpp
  src/effects/quadratic_damping.cpp
  src/effects/tangential_unbalance.cpp
  src/effects/magnet_offset.cpp
  src/effects/even_stiffness.cpp
  src/effects/linear_stiffness.cpp
  src/effects/viscous_damping.cpp
  src/effects/coulomb_friction.cpp
  src/effects/stribeck_friction.cpp
  src/effects/phase_offset.cpp
  src/effects/unbalance_scale.cpp
  src/effects/sensor_offset.cpp
  src/effects/sensor_gain.cpp
  src/effects/sensor_delay.cpp
  src/effects/unexplained.cpp
)
