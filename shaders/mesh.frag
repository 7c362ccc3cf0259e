#version 330 core
// Two-light Blinn-Phong with a hemispherical ambient term: readable shape on any background.
in vec3 vViewPosition;
in vec3 vViewNormal;
in vec3 vColor;

uniform vec3 uKeyLightDir;   // view space, towards the light
uniform vec3 uFillLightDir;
uniform float uWireframe;    // 1: dark flat colour (wireframe overlay); 2: flat colour (points)

out vec4 fragColor;

void main() {
  if (uWireframe > 1.5) {
    fragColor = vec4(pow(vColor, vec3(1.0 / 2.2)), 1.0);
    return;
  }
  if (uWireframe > 0.5) {
    fragColor = vec4(vColor * 0.25, 1.0);
    return;
  }
  vec3 n = normalize(vViewNormal);
  if (!gl_FrontFacing) n = -n;
  vec3 v = normalize(-vViewPosition);
  vec3 key = normalize(uKeyLightDir);
  vec3 fill = normalize(uFillLightDir);
  float ambient = mix(0.18, 0.32, 0.5 + 0.5 * n.y);
  float diffuse = 0.75 * max(dot(n, key), 0.0) + 0.25 * max(dot(n, fill), 0.0);
  float specular = 0.25 * pow(max(dot(n, normalize(key + v)), 0.0), 48.0);
  vec3 color = vColor * (ambient + diffuse) + vec3(specular);
  fragColor = vec4(pow(color, vec3(1.0 / 2.2)), 1.0);
}
