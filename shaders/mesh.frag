in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_color;     // sRGB
uniform float u_shadow;   // > 0: draw a flat shadow of this opacity instead of a lit surface
uniform float u_opacity;  // 1: opaque; less: a translucent pose, premultiplied for "over"

out vec4 out_color;

void main() {
  if (u_shadow > 0.0) {
    out_color = vec4(0.0, 0.0, 0.0, u_shadow);
    return;
  }
  vec3 lit = shade(srgb_to_linear(u_color), v_world_normal, v_world_position, 48.0, 0.25);
  out_color = vec4(linear_to_srgb(lit) * u_opacity, u_opacity);
}
