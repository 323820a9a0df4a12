// Writes nothing that is kept (colour writes are masked): the pass only sets the stencil.
out vec4 out_color;

void main() {
  out_color = vec4(1.0);
}
