// The effect registry: one line per named physical effect. A new effect is one file plus one line here.
// (impactlab fit also knows three effects that change the base model rather than add a force: bumper_offset,
// impact_duration and restitution; see core/src/identify/catalogue.cpp.)
#include "effects/effects.hpp"

namespace impactlab {

namespace {
constexpr const char* kSplineNames[] = {"lo", "hi", "c1", "c2", "c3", "c4", "c5", "c6"};
}  // namespace

const std::vector<EffectLaw>& effect_laws() {
    using N = std::array<const char*, kMaxLawParams>;
    const N spline_x{kSplineNames[0], kSplineNames[1], kSplineNames[2], kSplineNames[3], kSplineNames[4],
                     kSplineNames[5], kSplineNames[6], kSplineNames[7]};
    const N spline_x_units{"m", "m", "N", "N", "N", "N", "N", "N"};
    const N spline_v_units{"m/s", "m/s", "N", "N", "N", "N", "N", "N"};
    static const std::vector<EffectLaw> table{
        {"constant_force", "a constant force along the rail (a tilted rail)", {"F0", nullptr}, {"N", nullptr},
         {0.0}, effects::constant_force},
        {"quadratic_damping", "a resistance growing with the square of speed, -cq v|v|", {"cq", nullptr},
         {"N s^2/m^2", nullptr}, {0.0}, effects::quadratic_damping},
        {"tangential_unbalance", "the unbalance's tangential force -m0e phi'' cos(phi) (motor speed changes)",
         {"scale", nullptr}, {"-", nullptr}, {1.0}, effects::tangential_unbalance},
        {"magnet_offset", "the fixed magnet sits d off x = 0 (misaligned magnets): F_mag acts at x - d",
         {"d", "a1", "a3", "b2", "b4", nullptr}, {"m", "N/m", "N/m^3", "1/m^2", "1/m^4", nullptr},
         {0.0, -1763.5, 0.0, 4907.6, 0.0}, effects::magnet_offset},
        {"even_stiffness", "an even stiffness term -k2 x^2 (asymmetric magnets or springs)", {"k2", nullptr},
         {"N/m^2", nullptr}, {0.0}, effects::even_stiffness},
        {"linear_stiffness", "a change of the spring rate, -dk x", {"dk", nullptr}, {"N/m", nullptr}, {0.0},
         effects::linear_stiffness},
        {"viscous_damping", "a change of the viscous bearing resistance, -dc v", {"dc", nullptr},
         {"N s/m", nullptr}, {0.0}, effects::viscous_damping},
        {"coulomb_friction", "a change of the dry rolling resistance, -dT sign(v)", {"dT", nullptr},
         {"N", nullptr}, {0.0}, effects::coulomb_friction},
        {"stribeck_friction", "extra friction at low speed fading above vs, -Fs exp(-(v/vs)^2) sign(v)",
         {"Fs", "vs", nullptr}, {"N", "m/s", nullptr}, {0.0, 0.01}, effects::stribeck_friction},
        {"phase_offset", "the unbalance leads the measured angle by delta (encoder mark off)", {"delta", nullptr},
         {"rad", nullptr}, {0.0}, effects::phase_offset},
        {"unbalance_scale", "the unbalance is (1 + s) m0e instead of m0e", {"s", nullptr}, {"-", nullptr}, {0.0},
         effects::unbalance_scale},
        {"sensor_offset", "the position sensor reads x + o (no force; applied to the measurement)", {"o", nullptr},
         {"m", nullptr}, {0.0}, effects::sensor_offset},
        {"sensor_gain", "the position sensor reads g x (no force; applied to the measurement)", {"g", nullptr},
         {"-", nullptr}, {1.0}, effects::sensor_gain},
        {"unexplained_x", "a smooth force of the position x that no named effect explains", spline_x,
         spline_x_units, {0.0}, effects::unexplained_x},
        {"unexplained_v", "a smooth force of the velocity v that no named effect explains", spline_x,
         spline_v_units, {0.0}, effects::unexplained_v},
        {"unexplained_x_signv", "a force S(x) sign(v) (position-dependent friction) no named effect explains",
         spline_x, spline_x_units, {0.0}, effects::unexplained_x_signv},
        {"unexplained_phi", "a force periodic in the unbalance angle that no named effect explains",
         {"a1", "b1", "a2", "b2", "a3", "b3", nullptr}, {"N", "N", "N", "N", "N", "N", nullptr}, {0.0},
         effects::unexplained_phi},
    };
    return table;
}

}  // namespace impactlab
