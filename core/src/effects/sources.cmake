# Effect force laws, one file each (paths relative to core/). The table is src/effects/registry.cpp.
set(IMPACTLAB_EFFECT_SOURCES
  src/effects/constant_force.cpp
  src/effects/quadratic_damping.cpp
  src/effects/tangential_unbalance.cpp
)
