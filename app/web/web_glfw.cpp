// GLFW 3.3 calls that emscripten 3.1.6's GLFW lacks (gl_shim/GLFW/glfw3.h declares them).
#include <GLFW/glfw3.h>

// 1: emscripten 3.1.6's GLFW sizes the canvas in CSS pixels, so the UI is laid out in those whatever the
// screen's devicePixelRatio (the browser scales the canvas; Ctrl+= enlarges the UI as on the desktop).
extern "C" void glfwGetWindowContentScale(GLFWwindow*, float* xscale, float* yscale) {
    if (xscale) *xscale = 1.0f;
    if (yscale) *yscale = 1.0f;
}
