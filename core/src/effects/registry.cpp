// The effect registry: one line per named physical effect. A new effect is one file plus one line here.
#include "effects/effects.hpp"

namespace impactlab {

const std::vector<EffectLaw>& effect_laws() {
    static const std::vector<EffectLaw> table{
        {"constant_force", "a constant force along the rail (a tilted rail)", {"F0", nullptr}, {"N", nullptr},
         {0.0}, effects::constant_force},
        {"quadratic_damping", "a resistance growing with the square of speed, -cq v|v|", {"cq", nullptr},
         {"N s^2/m^2", nullptr}, {0.0}, effects::quadratic_damping},
        {"tangential_unbalance", "the unbalance's tangential force -m0e phi'' cos(phi) (motor speed changes)",
         {"scale", nullptr}, {"-", nullptr}, {1.0}, effects::tangential_unbalance},
    };
    return table;
}

}  // namespace impactlab
