#version 330 core
// Bodies, and their planar shadows (model then already flattens onto the floor).
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
// A model drawn in its own materials: linear albedo and texture coordinates per corner
// (meshes without them read the constant defaults, and the fragment shader ignores them).
layout(location = 2) in vec3 in_albedo;
layout(location = 3) in vec2 in_uv;

uniform mat4 u_model;
uniform mat4 u_view_projection;
uniform mat3 u_normal_matrix;
uniform vec3 u_color;  // sRGB

out vec3 v_world_position;
out vec3 v_world_normal;
out vec3 v_albedo;
out vec2 v_uv;
flat out vec3 v_color;

void main() {
  vec4 world = u_model * vec4(in_position, 1.0);
  v_world_position = world.xyz;
  v_world_normal = u_normal_matrix * in_normal;
  v_albedo = in_albedo;
  v_uv = in_uv;
  v_color = u_color;
  gl_Position = u_view_projection * world;
}
