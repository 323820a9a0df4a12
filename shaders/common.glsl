// Shared lighting: colours are linear inside, encoded to sRGB once at the end.
uniform vec3 u_light_direction;  // unit, the direction light travels
// The viewer: its position (w = 1, perspective) or the direction towards it (w = 0,
// orthographic: parallel rays), so that u_eye.xyz - u_eye.w * p points from p to the viewer.
uniform vec4 u_eye;

vec3 srgb_to_linear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(0.04045, c));
}
vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

// Blinn-Phong with a hemisphere ambient (sky above, ground bounce below).
vec3 shade(vec3 albedo, vec3 normal, vec3 position, float shininess, float specular) {
  vec3 n = normalize(normal);
  vec3 l = -u_light_direction;
  vec3 v = normalize(u_eye.xyz - u_eye.w * position);
  vec3 h = normalize(l + v);
  float diffuse = max(dot(n, l), 0.0);
  float spec = diffuse > 0.0 ? pow(max(dot(n, h), 0.0), shininess) * specular : 0.0;
  vec3 ambient = mix(vec3(0.20, 0.19, 0.18), vec3(0.38, 0.42, 0.48), 0.5 + 0.5 * n.y);
  return albedo * (ambient + 0.85 * diffuse) + vec3(spec);
}
