#include "impactlab/forces.hpp"

namespace impactlab {

double spring_magnet_potential(const Params& p, double x) {
    // 16-point Gauss-Legendre on [0, x].
    static constexpr double nodes[8] = {0.0950125098376374, 0.2816035507792589, 0.4580167776572274,
                                        0.6178762444026438, 0.7554044083550030, 0.8656312023878318,
                                        0.9445750230732326, 0.9894009349916499};
    static constexpr double weights[8] = {0.1894506104550685, 0.1826034150449236, 0.1691565193950025,
                                          0.1495959888165767, 0.1246289712555339, 0.0951585116824928,
                                          0.0622535239386479, 0.0271524594117541};
    const double half = 0.5 * x;
    double sum = 0.0;
    for (int i = 0; i < 8; ++i)
        sum += weights[i] * (spring_magnet(p, half * (1 + nodes[i])).F + spring_magnet(p, half * (1 - nodes[i])).F);
    return half * sum;
}

}  // namespace impactlab
