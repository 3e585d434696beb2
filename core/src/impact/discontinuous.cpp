#include "impact/discontinuous.hpp"

#include <cmath>

namespace impactlab::discontinuous {

double restitution(const double* p, double v_minus) {
    return (p[0] - p[1]) * std::exp(-p[2] * std::abs(v_minus)) + p[1];
}

double duration(const double* p, double v_minus) {
    return (p[3] - p[4]) * std::exp(-p[5] * std::abs(v_minus)) + p[4];
}

}  // namespace impactlab::discontinuous
