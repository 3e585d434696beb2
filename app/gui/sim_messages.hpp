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
    Section,   // a Poincare section point (phi = 2 pi n), located by the core
    Impact,    // a rigid impact began (G, H): force = v-, energy = impact duration
};

// One record of the sample ring: 64 bytes, one cache line.
struct SimMsg {
    double t = 0;        // [s]
    double x = 0;        // [m]
    double v = 0;        // [m/s]
    double phi = 0;      // unbalance angle, unwrapped [rad]; a Section has phi = 2 pi n exactly
    double omega = 0;    // [rad/s]
    double force = 0;    // bumper force [N] (Impact: the impact velocity v- [m/s])
    double energy = 0;   // mechanical energy [J] (Impact: the impact duration [s])
    std::uint32_t epoch = 0;   // bumped by every change of model, omega, xI or a reset
    MsgKind kind = MsgKind::Sample;
    Regime regime = Regime::Free;
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
};

struct SimCommand {
    CmdKind kind = CmdKind::SetPaused;
    double a = 0, b = 0;
    char model[24] = {};

    static SimCommand omega(double w) { return {CmdKind::SetOmega, w, 0, {}}; }
    static SimCommand xi(double x) { return {CmdKind::SetXI, x, 0, {}}; }
    static SimCommand paused(bool p) { return {CmdKind::SetPaused, p ? 1.0 : 0.0, 0, {}}; }
    static SimCommand step_period() { return {CmdKind::StepPeriod, 0, 0, {}}; }
    static SimCommand reset(double x0, double v0) { return {CmdKind::Reset, x0, v0, {}}; }
    static SimCommand speed(double s) { return {CmdKind::SetSpeed, s, 0, {}}; }
    static SimCommand set_model(std::string_view name) {
        SimCommand c{CmdKind::SetModel, 0, 0, {}};
        const std::size_t n = name.size() < sizeof(c.model) - 1 ? name.size() : sizeof(c.model) - 1;
        std::memcpy(c.model, name.data(), n);
        return c;
    }
};

}  // namespace impactlab::gui
