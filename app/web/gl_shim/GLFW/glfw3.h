// The web build's <GLFW/glfw3.h>: emscripten's own GLFW (-sUSE_GLFW=3), plus the GLFW 3.3 calls the
// desktop sources use that emscripten 3.1.6 lacks (defined in web_glfw.cpp).
#pragma once
#include_next <GLFW/glfw3.h>

#ifdef __cplusplus
extern "C" {
#endif
// 1 on both axes: the canvas is sized in CSS pixels (web_glfw.cpp).
void glfwGetWindowContentScale(GLFWwindow* window, float* xscale, float* yscale);
#ifdef __cplusplus
}
#endif
