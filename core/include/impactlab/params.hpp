// Model parameters: a model version is data. A Params value never changes while a simulation runs
// (MuJoCo's model/data split); everything that evolves lives in State (simulator.hpp).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace impactlab {

inline constexpr std::size_t kMaxLawParams = 8;
// The rail's travel either side of the springs' zero [m]: where F_SA must hold, where xI may stand, and
// beyond which a measured position is not the rig's.
inline constexpr double kRailHalfTravel = 0.1;

// Where a stiffness law's x lives: on the rig's rail in metres (Table 1), or in a record's own units (strain,
// volts: a plain Duffing law the fit starts from, with no rail, no bumper and no newtons).
enum class StiffnessKind { Rig, DataUnits };

// Stiffness law of Eq. (3): F_SA(x) = k x + (a1 x + a3 x^3 + a5 x^5 + a7 x^7) / (1 + b2 x^2 + ... + b8 x^8).
// Together with the bearing resistance and the unbalance it makes the "A" part of a version.
struct StiffnessSet {
    const char* id;                 // "A1", "A3"
    StiffnessKind kind;
    const char* summary;
    double m0e;                     // unbalance m0*e [kg m]
    double k;                       // mechanical springs [N/m]
    double c;                       // viscous bearing resistance [N s/m]
    double T;                       // dry rolling resistance [N]
    std::array<double, 4> a;        // a1 [N/m], a3 [N/m^3], a5, a7
    std::array<double, 4> b;        // b2 [1/m^2], b4 [1/m^4], b6, b8
};

// None: no bumper anywhere on the rail (a plain Duffing-type oscillator is a model like any other).
enum class ImpactKind { Compliant, Rigid, None };

// A contact force law for a compliant bumper: F >= 0 and its partial derivatives at penetration h >= 0
// and penetration rate hdot. dF_dh and dF_dhdot feed the implicit integrator's Newton matrix (dF_dhdot may
// be a bounded secant slope there); dF_dhdot_true is the true slope a tangent needs (NaN where a law does not
// give it: it is then taken by central differences).
struct ContactForce {
    double F, dF_dh, dF_dhdot;
    double dF_dhdot_true = NAN;
};
using ContactForceFn = ContactForce (*)(const double* p, double h, double hdot);
// A rigid (event-driven) law: restitution kappa(v-) and impact duration T_imp(v-) [s].
using ImpactFn = double (*)(const double* p, double v_minus);

// One row of the impact registry (impact/registry.cpp): a law plus one named parameter set.
struct ImpactModel {
    const char* id;                                 // "C", "C1", "G", "H"
    const char* summary;
    ImpactKind kind;
    std::array<const char*, kMaxLawParams> names;   // parameter names (JSON keys), nullptr-terminated
    std::array<const char*, kMaxLawParams> units;
    std::array<double, kMaxLawParams> defaults;     // SI units
    ContactForceFn contact = nullptr;               // Compliant only
    ImpactFn restitution = nullptr;                 // Rigid only
    ImpactFn duration = nullptr;                    // Rigid only
    double eps_v = 1e-4;                            // Rigid: |v+| below this may end in permanent contact [m/s]
};

// Where the cart is and how fast, with the forcing, as seen by an extra force law.
struct ForceContext {
    double t, x, v, phi, omega, alpha;   // alpha = phi'' [rad/s^2]
    double m0e, xI;
};
// An extra force on the cart (positive pushes towards +x) with its partial derivatives.
struct EffectForce { double F = 0, dF_dx = 0, dF_dv = 0, dF_dt = 0; };
using EffectForceFn = EffectForce (*)(const double* p, const ForceContext& ctx);

// What an effect changes: the force on the cart, or only what the position sensor reads (no force).
enum class EffectKind : std::uint8_t { Force, Sensor };

// When impactlab fit tries an effect (bits of EffectFitHint::needs).
struct FitNeeds {
    static constexpr unsigned Phi = 1;            // unbalance-forced data (the effect acts through phi)
    static constexpr unsigned SpeedChanges = 2;   // the motor's speed changes (phi'' is not negligible)
    static constexpr unsigned Magnets = 4;        // the model has a magnetic force to shift
    static constexpr unsigned DryFriction = 8;    // the model has dry friction T > 0
    static constexpr unsigned FixedBaseline = 16; // only when the base parameters are not fitted
    static constexpr unsigned XFeature = 32;      // the residual shows a narrow feature in x (identify/features.cpp)
    static constexpr unsigned VFeature = 64;      // ... in v
    static constexpr unsigned Cycle = 128;        // the residual's spring rate cycles slowly (identify/features.cpp)
};

inline constexpr std::array<double, kMaxLawParams> kUnboundedBelow{-1e12, -1e12, -1e12, -1e12, -1e12, -1e12, -1e12, -1e12};
inline constexpr std::array<double, kMaxLawParams> kUnboundedAbove{1e12, 1e12, 1e12, 1e12, 1e12, 1e12, 1e12, 1e12};

// How impactlab fit looks for an effect: which parameters it fits, how they enter, their bounds.
struct EffectFitHint {
    std::array<int, kMaxLawParams> free{};        // indices of the fitted parameters, n_free of them
    int n_free = 0;
    int n_linear = 0;                             // the first n_linear free ones enter the screening linearly
    std::array<double, kMaxLawParams> step{};     // per parameter: finite-difference step and natural scale
    std::array<double, kMaxLawParams> lo = kUnboundedBelow, hi = kUnboundedAbove;   // physical bounds
    std::array<double, 12> starts{};              // trial values of the first nonlinear free parameter
    int n_starts = 0;
    unsigned needs = 0;                           // FitNeeds bits
    const char* absorbed_by = nullptr;            // a base parameter that, when fitted, absorbs the effect
    bool positive = false;                        // the first linear parameter must come out > 0
    bool generic = false;                         // a last-resort smooth force named by its variable
    bool test_first_only = false;                 // significance of the first parameter alone (no null shape)
    bool from_reversals = false;                  // proposed from velocity reversals in the data, never screened
    // The generic terms of the law's variables (unexplained_x for a spring, unexplained_v for a damper, and a
    // second where its shape may also be read from another variable): the law is named only where none of them,
    // added beside it, predicts held-out data better.
    std::array<const char*, 2> rivals{};
    // A law that is a power n of one variable s (x or v), F = -c s|s|^(n-1) (odd) or -c |s|^n (even): its
    // shape is resolved only where the data tell it from the next power of its symmetry, n + 1 (0: not one).
    int power = 0;
    bool power_of_v = false, power_odd = true;
};

struct Params;

// What a description of a fitted effect may use.
struct EffectReportContext {
    const Params* model = nullptr;   // the model the effect was added to
    bool rig = true;                 // false: a plain Duffing model in the data's own units
    double v_typ = 0, x_typ = 0;     // RMS speed [m/s] and 90 % |x| [m] of the data
};
// One sentence for a fitted effect: values p and standard errors sigma (the law's parameter order).
using EffectDescribeFn = std::string (*)(const double* p, const double* sigma, const EffectReportContext& c);
// What a fit's starting shape parameters may use: the model and the data's ranges; `start` is the trial
// value of the first nonlinear free parameter.
struct EffectStartContext {
    const Params* model = nullptr;
    double x_lo = 0, x_hi = 0, v_lo = 0, v_hi = 0, start = 0;
    // Where the residual shows its narrowest strong feature in x and in v (lo == hi: none), true coordinates.
    double x_feature_lo = 0, x_feature_hi = 0, v_feature_lo = 0, v_feature_hi = 0;
    double cycle_period = 0;   // [s] the period of a slow cycle of the residual's spring rate (0: none)
};
using EffectStartFn = void (*)(double* p, const EffectStartContext& c);
// A sensor effect: what the sensor reads for the true position x (affine in x, unless the law is `curved`).
using EffectMeasureFn = double (*)(const double* p, double x);
// Copies into p what an effect shares with the model it is added to (magnet_offset: the magnetic law).
using EffectAdaptFn = void (*)(double* p, const Params& model);

// One row of the effect registry (effects/registry.cpp): a named physical effect the base model lacks, with
// everything the rest of the program needs to know about it (each effect's file defines its row).
struct EffectLaw {
    const char* id;                                 // stable snake_case id, e.g. "constant_force"
    const char* meaning;                            // one line of physics
    std::array<const char*, kMaxLawParams> names;   // nullptr-terminated
    std::array<const char*, kMaxLawParams> units;
    std::array<double, kMaxLawParams> defaults;
    EffectForceFn force;
    EffectKind kind = EffectKind::Force;
    EffectFitHint fit{};                            // n_free == 0: fit never looks for it
    EffectDescribeFn describe = nullptr;
    EffectStartFn start = nullptr;                  // null: free parameters from 0, the others from defaults
    EffectMeasureFn measure = nullptr;              // Sensor only
    bool curved = false;                            // Sensor only: a curve, read before the gains and offsets
    EffectAdaptFn adapt = nullptr;                  // null: nothing shared with the model
};

// An effect switched on in a parameter set.
struct EffectInstance {
    const EffectLaw* law = nullptr;
    std::array<double, kMaxLawParams> p{};
};

struct Params {
    std::string name = "A1H";       // version name, e.g. "A1H" or a user's label
    std::string stiffness_id = "A1";
    double m = 6.73766;             // cart mass [kg]
    double m0e = 0.025152;          // unbalance [kg m]
    double k = 1115.2;              // [N/m]
    double c = 12.373;              // [N s/m]
    double T = 1.2267;              // [N]
    double eps = 1e-6;              // friction smoothing [m/s]
    std::array<double, 4> a{};      // a1, a3, a5, a7
    std::array<double, 4> b{};      // b2, b4, b6, b8
    double xI = 0.0;                // bumper position [m]
    double input_gain = 0.0;        // force per unit of a sampled input u(t) [N per unit of u] (Drive::input)
    // Where the model's laws are checked (|x| <= x_extent, in the model's own unit of x); 0: the rail,
    // |x| <= 0.1 m, with forces a rail can take. A model in a record's units (strain, volts) carries the
    // extent of its record, and its forces are checked for being finite there, with no ceiling in newtons.
    double x_extent = 0.0;
    const ImpactModel* impact = nullptr;            // never null in a valid Params
    std::array<double, kMaxLawParams> ip{};         // impact law parameters (impact->names order)
    std::vector<EffectInstance> effects;            // extra force laws (identify/, effects/)

    bool rigid() const { return impact->kind == ImpactKind::Rigid; }
    bool compliant() const { return impact->kind == ImpactKind::Compliant; }
    bool has_bumper() const { return impact->kind != ImpactKind::None; }
};

// Thrown for any invalid parameter set: the message names the source, the key and the problem.
struct ParamError : std::runtime_error { using std::runtime_error::runtime_error; };

// Registries: explicit tables, one line per entry.
const std::vector<StiffnessSet>& stiffness_sets();
const std::vector<ImpactModel>& impact_models();
const std::vector<EffectLaw>& effect_laws();
// A Table 1 row, or the plain Duffing law ("duffing", in data units), which no version is made of.
const StiffnessSet* find_stiffness(const std::string& id);
const StiffnessSet& duffing_stiffness();
// The kind of p's stiffness law (Rig for an id no row has).
StiffnessKind stiffness_kind(const Params& p);
const ImpactModel* find_impact(const std::string& id);
const EffectLaw* find_effect(const std::string& id);

// "A1H", "A3C1", ...: any stiffness id followed by any impact id. Throws ParamError for an unknown name.
Params make_version(const std::string& name);
// All XY combinations, paper's versions first.
std::vector<std::string> version_names();
// The physically meaningful range of a parameter: validate refuses values outside it, naming key and range
// (`impactlab models` prints the table). Keys are the JSON keys; "impact.X" for the impact law's.
struct ParamRange {
    const char* key;
    double lo, hi;
    const char* unit;
    const char* why;
};
const std::vector<ParamRange>& param_ranges();
// The largest force any law (stiffness, bumper, effect) may exert on the rail |x| <= 0.1 m at |v| <= 10 m/s
// and omega <= 1000 rad/s [N]: a law beyond it is a typo or a unit slip, and would make the equations stall.
inline constexpr double kMaxLawForce = 1e8;
// Checks every value (finite, signs, ranges, forces); throws ParamError naming `source` and the key.
void validate(const Params& p, const std::string& source = "parameters");
// validate's force checks for the laws that change with time (magnet_drift, stiffness_drift, ...), over the
// times [t_begin, t_end] a run or record spans: a drift harmless at t = 0 may be beyond any rig by its end.
void validate_over(const Params& p, double t_begin, double t_end, const std::string& source = "parameters");
// Value of an impact-law parameter by name; throws ParamError if the law has no such parameter.
double impact_param(const Params& p, const std::string& key);
void set_impact_param(Params& p, const std::string& key, double value);
// Adds an effect with its default parameters; returns it for the caller to set values.
EffectInstance& add_effect(Params& p, const std::string& id);

}  // namespace impactlab
