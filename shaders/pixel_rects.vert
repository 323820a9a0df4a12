#version 330 core
// Rectangles given in pixels (two triangles each), for marking exactly their pixels in the
// stencil: corners lie on pixel edges, so a pixel's centre is half a pixel from any of them and
// rounding cannot change which pixels are covered.
layout(location = 0) in vec2 in_pixel;

uniform vec2 u_pixel;  // 1 / size

void main() {
  gl_Position = vec4(in_pixel * (2.0 * u_pixel) - 1.0, 0.0, 1.0);
}
