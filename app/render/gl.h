// The one place OpenGL is included. We link libglvnd's libOpenGL, which exports every core
// entry point and dispatches to the current context, GLX (GLFW window) or EGL (offscreen).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
