// The one place the viewer includes OpenGL. GL 3.3 core functions are declared by the Khronos
// core header and resolved at link time against libOpenGL (glvnd), which dispatches to the
// vendor library of whatever context is current: GLX (GLFW windows) or EGL (headless).
// No loader, no generated code; every function used here is core since OpenGL 3.3.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
