#version 330 core
// Surface vertices in world space; lighting is done per fragment in view space.
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aColor;

uniform mat4 uView;
uniform mat4 uProjection;
uniform float uPointSize;

out vec3 vViewPosition;
out vec3 vViewNormal;
out vec3 vColor;

void main() {
  vec4 viewPosition = uView * vec4(aPosition, 1.0);
  vViewPosition = viewPosition.xyz;
  vViewNormal = mat3(uView) * aNormal;
  vColor = aColor;
  gl_Position = uProjection * viewPosition;
  gl_PointSize = uPointSize;
}
