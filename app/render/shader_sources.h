// Shader sources from shaders/, embedded at build time so the binary runs from anywhere.
#pragma once

namespace galsculpt::shaders {
extern const char* const kMeshVert;
extern const char* const kMeshFrag;
}  // namespace galsculpt::shaders
