// What travels between the UI thread and the simulation thread: plain, trivially copyable records for the
// two SPSC rings (samples out, commands in). GL-free; the headless tests use them too.
#pragma once

#include <cstdint>
#include <cstring>
#include <string_view>

#include "impactlab/simulator.hpp"

namespace impactlab::gui {

enum class MsgKind : std::uint8_t {
    Sample,    // the trajectory at a fixed sim-time step
    Section,   // a Poincare section point (phi = phi0 + 2 pi k, phi0 the section phase), located by the core
    Impact,    // a rigid impact began (G, H): force = v-, energy = impact duration
    Grazing,   // the grazing monitor, once per forcing period at its section (GrazingMonitor::Period):
               // x = the largest x over the period [m], v = the last impact's v- (rigid) or entry velocity
               // (compliant) in it [m/s], NaN if none; force = the deepest penetration (compliant) [m];
               // energy = the impacts (contacts) in the period
};

// One record of the sample ring: 64 bytes, one cache line.
struct SimMsg {
    double t = 0;        // [s]
    double x = 0;        // [m]
    double v = 0;        // [m/s]
    double phi = 0;      // unbalance angle, unwrapped [rad]; a Section has phi = phi0 mod 2 pi
    double omega = 0;    // [rad/s]
    double force = 0;    // bumper force [N] (Impact: the impact velocity v- [m/s])
    double energy = 0;   // mechanical energy [J] (Impact: the impact duration [s])
    std::uint32_t epoch = 0;   // bumped by every change of model, omega, xI, section phase or a reset
    MsgKind kind = MsgKind::Sample;
    Regime regime = Regime::Free;
    std::uint8_t source = 0;   // 0: the cart; 1: its companion (the twin or the ghost, CompanionMode)
};
static_assert(sizeof(SimMsg) == 64, "one sample, one cache line");

enum class CmdKind : std::uint8_t {
    SetOmega,     // a = omega [rad/s]; the phase stays continuous
    SetXI,        // a = bumper position [m]
    SetModel,     // model = version name ("A1H"); x, v, phi and xI are kept
    SetPaused,    // a != 0: pause
    StepPeriod,   // run to the next Poincare section (one forcing period), then pause
    Reset,        // t = 0, phi = 0, x = a, v = b
    SetSpeed,     // a = real-time factor, 0.01 .. 100
    SetState,     // x = a [m], v = b [m/s] from now (the mouse); t and phi go on. Clamped to the rail, never
                  // beyond the bumper
    Hold,         // the cart is held at x = a (the mouse drags it): time and phi go on, nothing is integrated
                  // until the next SetState or Reset lets it go
    SetCompanion, // a = CompanionMode (0 off, 1 twin, 2 ghost), b = the twin's offset [m], model = the ghost's
                  // version; the companion starts from the cart's state now
    Ramp,         // omega moves linearly from its value now to a [rad/s] at b [rad/s per s of sim time], phi
                  // continuous (the paper's EF protocol, live); any other omega command or Reset ends it
    Restart,      // continue from a replayed instant or a saved session: x = a [m], v = b [m/s], t = t0 [s],
                  // phi = phi0 [rad] (unwrapped), at the omega running now; what came after t0 is dropped
    SetParam,     // model = a parameter's key ("k", "kappa0", ...; param_edit.hpp), a = its value; x, v, phi
                  // kept. A value the core's validate() refuses changes nothing
    ResetParams,  // every parameter back to the running version's own values; x, v, phi kept
    SetSectionPhase,   // a = the Poincare section phase phi0 [rad], 0 .. 2 pi: sections at phi0 + 2 pi k
                       // from now; the run goes on, a new epoch (the map's points are of another section)
};

// The second cart that runs beside the first in lockstep.
enum class CompanionMode : std::uint8_t {
    Off = 0,
    Twin = 1,    // the same model from x + 1 um: sensitivity to initial conditions
    Ghost = 2,   // the same state under another model (another impact law)
};
inline constexpr double kTwinOffset = 1e-6;   // [m]

struct SimCommand {
    CmdKind kind = CmdKind::SetPaused;
    double a = 0, b = 0;
    char model[24] = {};
    double t0 = 0, phi0 = 0;   // Restart only

    static SimCommand omega(double w) { return {CmdKind::SetOmega, w, 0, {}}; }
    static SimCommand xi(double x) { return {CmdKind::SetXI, x, 0, {}}; }
    static SimCommand paused(bool p) { return {CmdKind::SetPaused, p ? 1.0 : 0.0, 0, {}}; }
    static SimCommand step_period() { return {CmdKind::StepPeriod, 0, 0, {}}; }
    static SimCommand reset(double x0, double v0) { return {CmdKind::Reset, x0, v0, {}}; }
    static SimCommand speed(double s) { return {CmdKind::SetSpeed, s, 0, {}}; }
    static SimCommand ramp(double omega_to, double rate) { return {CmdKind::Ramp, omega_to, rate, {}}; }
    static SimCommand restart(double x, double v, double t, double phi) {
        SimCommand r{CmdKind::Restart, x, v, {}};
        r.t0 = t;
        r.phi0 = phi;
        return r;
    }
    static SimCommand set_state(double x, double v) { return {CmdKind::SetState, x, v, {}}; }
    static SimCommand hold(double x) { return {CmdKind::Hold, x, 0, {}}; }
    static SimCommand companion(CompanionMode mode, std::string_view ghost_model = {}, double offset = kTwinOffset) {
        SimCommand c = set_model(ghost_model);
        c.kind = CmdKind::SetCompanion;
        c.a = static_cast<double>(mode);
        c.b = offset;
        return c;
    }
    static SimCommand set_param(std::string_view key, double value) {
        SimCommand c = set_model(key);
        c.kind = CmdKind::SetParam;
        c.a = value;
        return c;
    }
    static SimCommand reset_params() { return {CmdKind::ResetParams, 0, 0, {}}; }
    static SimCommand section_phase(double phi0) { return {CmdKind::SetSectionPhase, phi0, 0, {}}; }
    static SimCommand set_model(std::string_view name) {
        SimCommand c{CmdKind::SetModel, 0, 0, {}};
        const std::size_t n = name.size() < sizeof(c.model) - 1 ? name.size() : sizeof(c.model) - 1;
        if (n > 0) std::memcpy(c.model, name.data(), n);   // an empty view's data() may be null
        return c;
    }
};

}  // namespace impactlab::gui
