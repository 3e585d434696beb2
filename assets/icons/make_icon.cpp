// Draws the window icon: a blue cart with the spinning unbalance (orange mass) on a dark tile.
#include <stb_image_write.h>
#include <cmath>
#include <vector>
#include <algorithm>
// Build and run by hand: g++ -I/usr/include/stb make_icon.cpp -lstb && ./a.out impactlab-64.png
int main(int argc, char** argv) {
    const int N = 64; std::vector<unsigned char> px(N * N * 4, 0);
    auto blend = [&](int x, int y, float r, float g, float b, float a) {
        unsigned char* p = &px[(y * N + x) * 4];
        float da = p[3] / 255.f, oa = a + da * (1 - a);
        for (int c = 0; c < 3; ++c) { float s = c == 0 ? r : c == 1 ? g : b; float d = p[c] / 255.f;
            p[c] = (unsigned char)(255 * (oa > 0 ? (s * a + d * da * (1 - a)) / oa : 0)); }
        p[3] = (unsigned char)(255 * oa);
    };
    auto sdbox = [](float px, float py, float cx, float cy, float hx, float hy, float r) {
        float qx = std::abs(px - cx) - hx + r, qy = std::abs(py - cy) - hy + r;
        return std::hypot(std::max(qx, 0.f), std::max(qy, 0.f)) + std::min(std::max(qx, qy), 0.f) - r; };
    for (int y = 0; y < N; ++y) for (int x = 0; x < N; ++x) {
        float fx = x + 0.5f, fy = y + 0.5f;
        auto cov = [](float d) { return std::clamp(0.5f - d, 0.f, 1.f); };
        blend(x, y, 0.10f, 0.12f, 0.16f, cov(sdbox(fx, fy, 32, 32, 31, 31, 10)));          // tile
        blend(x, y, 0.62f, 0.65f, 0.70f, cov(std::abs(fy - 48) - 2.0f) * cov(std::abs(fx - 32) - 26)); // rail
        blend(x, y, 0.20f, 0.42f, 0.72f, cov(sdbox(fx, fy, 30, 30, 17, 15, 4)));          // cart
        blend(x, y, 0.70f, 0.72f, 0.76f, cov(std::hypot(fx - 30, fy - 30) - 10.5f));      // disc
        blend(x, y, 1.0f, 0.35f, 0.15f, cov(sdbox(fx, fy, 55, 30, 3, 9, 1.5f)));          // hot bumper
        float mx = 30 + 6.5f * std::sin(2.2f), my = 30 - 6.5f * std::cos(2.2f);
        blend(x, y, 0.95f, 0.62f, 0.15f, cov(std::hypot(fx - mx, fy - my) - 4.2f));       // mass
        blend(x, y, 0.45f, 0.47f, 0.52f, cov(std::hypot(fx - 30, fy - 30) - 2.0f));       // hub
    }
    stbi_write_png(argc > 1 ? argv[1] : "impactlab-64.png", N, N, 4, px.data(), N * 4);
}
