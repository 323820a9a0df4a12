in vec3 v_world_position;
in vec3 v_world_normal;
in vec3 v_albedo;
in vec2 v_uv;
flat in vec3 v_color;  // sRGB: the body's (mesh.vert's u_color, or its instance's)

uniform float u_shadow;   // > 0: draw a flat shadow of this opacity instead of a lit surface
uniform float u_opacity;  // 1: opaque; less: a translucent pose, premultiplied for "over"
// A model in its own materials: the albedo comes per corner (linear: material colour × vertex
// colour), times the texture where the material has one (sRGB texels, decoded by the sampler).
uniform bool u_material;
uniform bool u_textured;
uniform sampler2D u_texture;

out vec4 out_color;

void main() {
  if (u_shadow > 0.0) {
    out_color = vec4(0.0, 0.0, 0.0, u_shadow);
    return;
  }
  vec3 albedo = srgb_to_linear(v_color);
  if (u_material) albedo = v_albedo * (u_textured ? texture(u_texture, v_uv).rgb : vec3(1.0));
  vec3 lit = shade(albedo, v_world_normal, v_world_position, 48.0, 0.25);
  out_color = vec4(linear_to_srgb(lit) * u_opacity, u_opacity);
}
