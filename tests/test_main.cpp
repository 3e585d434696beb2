// The tests are a program like the others: they hand core's plot layer the font found for them (the
// source tree's assets/) before any figure is drawn.
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include "program_assets.hpp"

int main(int argc, char** argv) {
    impactlab::use_program_fonts();
    doctest::Context context(argc, argv);
    return context.run();
}
