#version 330 core
// Bodies that share a model (boxes: the cube, spheres: the ball, particles: the sphere), and
// their planar shadows, many in one draw: each instance brings its model matrix, normal matrix
// and colour. The same arithmetic as mesh.vert, so the same pixels as drawing them one by one.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 4) in mat4 in_model;          // locations 4-7
layout(location = 8) in mat3 in_normal_matrix;  // locations 8-10
layout(location = 11) in vec3 in_color;         // sRGB

uniform mat4 u_view_projection;

out vec3 v_world_position;
out vec3 v_world_normal;
out vec3 v_albedo;
out vec2 v_uv;
flat out vec3 v_color;

void main() {
  vec4 world = in_model * vec4(in_position, 1.0);
  v_world_position = world.xyz;
  v_world_normal = in_normal_matrix * in_normal;
  v_albedo = vec3(1.0);  // the shared models have no materials (mesh.frag ignores it)
  v_uv = vec2(0.0);
  v_color = in_color;
  gl_Position = u_view_projection * world;
}
