// The web build's <GL/gl.h>: OpenGL ES 3.0 (WebGL2) under the name the desktop sources include.
#pragma once
#include <GLES3/gl3.h>
