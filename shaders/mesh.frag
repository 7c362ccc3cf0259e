#version 330 core
// Two-light Blinn-Phong with a hemispherical ambient term: readable shape on any background.
in vec3 vViewPosition;
in vec3 vViewNormal;
in vec3 vColor;

uniform vec3 uKeyLightDir;   // view space, towards the light
uniform vec3 uFillLightDir;
uniform float uWireframe;    // 1: dark flat colour (wireframe overlay); 2: flat colour (points)

out vec4 fragColor;

// c^(1/2.2) within 1/255 on [0, 1] from two square roots: a software rasterizer (llvmpipe) pays
// several times more for pow's exp2 and log2 on every pixel of the body.
vec3 toDisplay(vec3 c) {
  vec3 s = sqrt(max(c, vec3(0.0)));
  return 0.955033 * s + 0.0955068 * sqrt(s) - 0.0511598 * c;
}

void main() {
  if (uWireframe > 1.5) {
    fragColor = vec4(toDisplay(vColor), 1.0);
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
  // h^48 as h^32 h^16 by squaring (pow, as above, costs a software rasterizer far more).
  float h = max(dot(n, normalize(key + v)), 0.0);
  float h2 = h * h, h4 = h2 * h2, h8 = h4 * h4, h16 = h8 * h8;
  float specular = 0.25 * h16 * h16 * h16;
  vec3 color = vColor * (ambient + diffuse) + vec3(specular);
  fragColor = vec4(toDisplay(color), 1.0);
}
