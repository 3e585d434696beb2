// The web build's <GL/glext.h>: everything the GUI uses is core OpenGL ES 3.0 (<GL/gl.h> here).
#pragma once
#include <GLES3/gl3.h>
