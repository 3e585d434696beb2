#include "history.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

namespace impactlab::gui {

namespace {
struct File {
    std::FILE* f;
    explicit File(const std::string& path) : f(std::fopen(path.c_str(), "w")) {}
    ~File() {
        if (f) std::fclose(f);
    }
    bool close() {
        const bool ok = f && std::ferror(f) == 0;
        const bool closed = f && std::fclose(f) == 0;
        f = nullptr;
        return ok && closed;
    }
};
}  // namespace

bool write_trajectory_csv(const std::string& path, const History<SimMsg>& h, const std::string& model) {
    File out(path);
    if (!out.f) return false;
    std::fprintf(out.f,
                 "# impactlab-gui trajectory\n# model: %s (at export; the epoch column changes with every change of "
                 "model, omega or x_I and at every reset)\n# units: SI (s, m, m/s, rad, rad/s, N, J); regime: 1 free "
                 "flight, 2 sticking, 3 permanent contact\n",
                 model.c_str());
    std::fprintf(out.f, "t,x,v,phi,omega,regime,bumper_force,energy,epoch\n");
    for (std::size_t i = 0; i < h.size(); ++i) {
        const SimMsg& m = h[i];
        std::fprintf(out.f, "%.9f,%.9e,%.9e,%.9f,%.6f,%d,%.6e,%.9e,%u\n", m.t, m.x, m.v, m.phi, m.omega,
                     static_cast<int>(m.regime), m.force, m.energy, m.epoch);
    }
    return out.close();
}

bool write_sections_csv(const std::string& path, const History<SimMsg>& s, const std::string& model) {
    File out(path);
    if (!out.f) return false;
    std::fprintf(out.f, "# impactlab-gui Poincare section (phi = 2 pi n)\n# model: %s\n# units: SI\n", model.c_str());
    std::fprintf(out.f, "n,t,x,v,omega,regime\n");
    for (std::size_t i = 0; i < s.size(); ++i) {
        const SimMsg& m = s[i];
        const long long n = std::llround(m.phi / kTwoPi);
        std::fprintf(out.f, "%lld,%.9f,%.9e,%.9e,%.6f,%d\n", n, m.t, m.x, m.v, m.omega, static_cast<int>(m.regime));
    }
    return out.close();
}

}  // namespace impactlab::gui
