// --state-json: what the panels show after a headless run, for tests and scripts (App::write_state_json).
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app.hpp"

namespace impactlab::gui {

namespace {
// NaN and infinities have no JSON spelling: null.
nlohmann::json number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

// UI thread, after the last frame.
bool App::write_state_json(const std::string& path) {
    using nlohmann::json;
    json j;
    j["model"] = model_name();
    j["omega"] = number(omega_);
    j["xI"] = number(xI_);
    j["speed"] = number(speed_);
    j["preset"] = opt_.preset > 0 ? json(presets_for(model_name())[static_cast<std::size_t>(opt_.preset - 1)].label)
                                  : json(nullptr);
    j["sim_time"] = number(have_last_ ? last_.t : sim_->status().sim_time);
    j["fps"] = number(fps_);
    j["frames"] = frame_count_;
    j["epoch"] = epoch_;
    j["energy"] = number(last_.energy);                 // [J] now
    j["energy_max_trail"] = number(trail_e_max_);       // [J] over the phase portrait's trail
    j["potential_view"] = {potential_y_.cur.lo, potential_y_.cur.hi};   // [J] the potential plot's y range
    const PoincareMap::Status st = pc_map_.status();
    j["poincare_status"] = st == PoincareMap::Status::Periodic ? "periodic"
                           : st == PoincareMap::Status::Chaotic ? "chaos" : "settling";
    j["poincare_period"] = st == PoincareMap::Status::Settling ? json(nullptr) : json(pc_map_.period());
    j["poincare_seen"] = pc_map_.seen();   // section points since the last change, the transient included
    j["poincare_tol"] = {pc_map_.tol_x(), pc_map_.tol_v()};
    json pts = json::array(), imp = json::array();
    const History<MapPoint>& h = pc_map_.points();
    for (std::size_t i = 0; i < h.size(); ++i) {
        pts.push_back({h[i].x, h[i].v});
        imp.push_back(h[i].impacts);
    }
    j["poincare_points"] = std::move(pts);
    j["poincare_impacts"] = std::move(imp);   // impacts in the forcing period ending at each point

    // Written whole: a temporary beside the target, then renamed over it.
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::trunc);
        f << j.dump(1) << '\n';
        if (!f) {
            std::fprintf(stderr, "impactlab-gui: error: --state-json: cannot write '%s'\n", path.c_str());
            return false;
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        std::fprintf(stderr, "impactlab-gui: error: --state-json: cannot write '%s'\n", path.c_str());
        return false;
    }
    return true;
}

}  // namespace impactlab::gui
