// Session files: the visualiser's whole state as JSON, saved and loaded by the app (File menu,
// Ctrl+S / Ctrl+O, --session / --save-session). This part is GL-free: the state as a plain struct, its JSON
// and the validation of a file, which either yields a complete Session or a SessionError naming the file,
// the key (and the line of a parse error) and the problem. The app applies a Session only once it is valid,
// so a bad file leaves everything as it was.
#pragma once

#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace impactlab::gui {

struct SessionError : std::runtime_error { using std::runtime_error::runtime_error; };

// A plot the user zoomed or panned: its id (the plot's ImGui id, "##phase") and the view shown.
struct SessionView {
    std::string id;
    double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;   // data units (SI)
    bool operator==(const SessionView&) const = default;
};

// A Poincare clicker's orbit: where it was started and its section points [m, m/s].
struct SessionOrbit {
    double x0 = 0, v0 = 0;
    std::vector<std::pair<double, double>> points;
    bool operator==(const SessionOrbit&) const = default;
};
inline constexpr std::size_t kSessionMaxOrbits = 8, kSessionMaxOrbitPoints = 4000;

struct Session {
    // Model and forcing (what the GUI changes of the parameters).
    std::string model = "A1H";           // a version name (make_version)
    double omega = 9.0;                  // [rad/s], 0 .. 30
    double xI = 0.0;                     // [m], -0.02 .. 0.02
    double speed = 1.0;                  // real-time factor, 0.01 .. 100
    bool paused = false;
    // The simulation state the run continues from.
    double t = 0, x = -0.011, v = 0, phi = 0;   // [s], [m], [m/s], [rad] (unwrapped)
    // View.
    bool dark = true;
    double ui_scale = 1.0;               // 0.5 .. 3
    double trail_periods = 8.0;          // phase portrait trail [forcing periods], 1 .. 60
    double strip_window = 6.0;           // x(t) strip [s], 0.5 .. 60
    double poincare_phi0 = 0.0;          // the Poincare section's phase [rad], 0 .. 2 pi
    std::vector<SessionView> views;      // zoomed plots only
    bool show_data = false, show_help = false;   // windows open
    // The bifurcation diagram's settings (not the diagram: it is recomputed on demand).
    std::string bif_protocol = "cf-up";  // cf-up, cf-down, ef
    int bif_steps = 300;                 // 10 .. 2000
    std::string data;                    // the measured-data file loaded ("" none)
    // The companion cart beside the first (off, twin, ghost) and the ghost's impact law (an impact id).
    std::string companion = "off";
    std::string ghost_impact = "G";
    // The layout: presentation mode or not, the panels hidden (layout.hpp's panel keys, and "controls" for
    // the column), the one maximised ("" none), presentation's plot, and the rig's displacement
    // magnification in each mode (1 .. 10). ui_scale above is the normal mode's (presenting raises it).
    bool presentation = false;
    std::vector<std::string> hidden;
    std::string maximised;
    std::string presentation_plot = "phase";
    double magnify = 1.0, magnify_presentation = 3.0;
    // The parameters edited in the Parameters panel (key, value), applied to the model's own after it.
    std::vector<std::pair<std::string, double>> params;
    // The time strip's traces: one or two of x, v, E, F, drive.
    std::vector<std::string> strip{"x"};
    // The Poincare clicker: on or off, and each orbit's start and section points as they were.
    bool clicker = false;
    std::vector<SessionOrbit> orbits;
    bool operator==(const Session&) const = default;
};

inline constexpr const char* kSessionFormat = "impactlab-gui session";
inline constexpr int kSessionVersion = 1;

nlohmann::json session_to_json(const Session& s);
// Validates j whole. Keys that are absent keep their value in `base` (a session file may set only some);
// an unknown key, a wrong type or a value out of range throws SessionError("FILE: key 'K': problem").
// `file` names the source in messages.
Session session_from_json(const nlohmann::json& j, const Session& base, const std::string& file);
// Parses text (a parse error names its line and column) and validates it.
Session parse_session(const std::string& text, const Session& base, const std::string& file);
// Reads and validates a file ("FILE: cannot read it (...)" when missing).
Session load_session(const std::string& path, const Session& base);
// Writes the file whole (a partial file renamed over it); throws SessionError naming it.
void save_session(const Session& s, const std::string& path);
// The text save_session writes (pretty-printed JSON with a final newline).
std::string session_text(const Session& s);

}  // namespace impactlab::gui
