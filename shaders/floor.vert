#version 330 core
// A large square at the floor height; the checker is computed per pixel.
layout(location = 0) in vec3 in_position;

uniform mat4 u_model;
uniform mat4 u_view_projection;

out vec3 v_world_position;

void main() {
  vec4 world = u_model * vec4(in_position, 1.0);
  v_world_position = world.xyz;
  gl_Position = u_view_projection * world;
}
