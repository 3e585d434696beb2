// A version with no springs, no magnets, no resistance and no forcing, the bumper at x = 0: the cart coasts
// at constant velocity between contacts, so an impact's own law is all that acts (impact and energy tests).
// harmonic() adds a linear spring: m x'' + k x = 0 with omega0 = 10 rad/s, the bumper at xI (closed forms).
#pragma once

#include "impactlab/params.hpp"

namespace impactlab::testing {

inline Params coasting(const char* version) {
    Params p = make_version(version);
    p.k = 0;
    p.a = {};
    p.b = {};
    p.c = 0;
    p.T = 0;
    p.m0e = 0;
    p.xI = 0;
    return p;
}

inline Params harmonic(const char* version, double xI = 0.0) {
    Params p = coasting(version);
    p.m = 1.0;
    p.k = 100.0;
    p.xI = xI;
    return p;
}

}  // namespace impactlab::testing
