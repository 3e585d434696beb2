// GLFW 3.3 calls that emscripten 3.1.6's GLFW lacks (gl_shim/GLFW/glfw3.h declares them).
#include <emscripten.h>
#include <GLFW/glfw3.h>

extern "C" void glfwGetWindowContentScale(GLFWwindow*, float* xscale, float* yscale) {
    const float s = static_cast<float>(emscripten_get_device_pixel_ratio());
    if (xscale) *xscale = s;
    if (yscale) *yscale = s;
}
