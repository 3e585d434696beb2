// The impact registry: one line per model version (Tables 2 and 3 of the paper, as MODEL.md reads them).
// A new impact model is one law file plus one line here.
#include "impact/discontinuous.hpp"
#include "impact/hunt_crossley.hpp"
#include "impactlab/params.hpp"

namespace impactlab {

namespace {
constexpr std::array<const char*, kMaxLawParams> kHcNames{"kI", "b", "n1", "n2", "n3", nullptr};
constexpr std::array<const char*, kMaxLawParams> kHcUnits{"N/m^n1", "(s/m)^n3", "-", "-", "-", nullptr};
constexpr std::array<const char*, kMaxLawParams> kRigidNames{"kappa0", "kappa1", "a_kappa", "Ti0", "Ti1", "a_T",
                                                             nullptr};
constexpr std::array<const char*, kMaxLawParams> kRigidUnits{"-", "-", "s/m", "s", "s", "s/m", nullptr};
}  // namespace

const std::vector<ImpactModel>& impact_models() {
    static const std::vector<ImpactModel> table{
        {"C", "compliant Hunt-Crossley bumper, kI identified", ImpactKind::Compliant, kHcNames, kHcUnits,
         {2.3983e8, 0.8485, 1.5, 1.5, 0.18667}, hunt_crossley::contact, nullptr, nullptr},
        {"C1", "compliant Hunt-Crossley bumper, very stiff (kI = 1e12)", ImpactKind::Compliant, kHcNames, kHcUnits,
         {1e12, 0.84208, 1.5, 1.5, 0.18619}, hunt_crossley::contact, nullptr, nullptr},
        {"G", "rigid bumper, instantaneous impact, restitution kappa(v-)", ImpactKind::Rigid, kRigidNames,
         kRigidUnits, {0.6242, 0.0, 0.5061, 0.0, 0.0, 0.0}, nullptr, discontinuous::restitution,
         discontinuous::duration},
        {"H", "rigid bumper, finite impact duration T_imp(v-), restitution kappa(v-)", ImpactKind::Rigid,
         kRigidNames, kRigidUnits, {0.6150, 0.1350, 0.6594, 6.2193e-3, 4.0689e-3, 2.1733}, nullptr,
         discontinuous::restitution, discontinuous::duration},
        {"none", "no bumper: the cart moves freely past xI (a plain Duffing-type oscillator)", ImpactKind::None,
         {nullptr}, {nullptr}, {}, nullptr, nullptr, nullptr},
    };
    return table;
}

}  // namespace impactlab
