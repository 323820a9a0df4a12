in vec3 v_world_position;

uniform vec3 u_tile_light;   // sRGB, lit (the floor is flat: its lighting is one colour per tile)
uniform vec3 u_tile_dark;    // sRGB, lit
uniform vec3 u_background;   // sRGB
uniform bool u_transparent;  // the backdrop is transparent: fade into alpha 0, not the sky
uniform vec2 u_fade_centre;  // xz where the floor is drawn in full
uniform vec2 u_fade_axis;    // (0, 0): fade with the distance from the centre; else along this
                             // unit direction only (an orthographic camera's depth)
uniform float u_fade_start;  // metres from the centre where it starts to fade away
uniform float u_fade_end;
uniform float u_checker_m;   // the side of a square, m (a power of ten near the bodies' size)

out vec4 out_color;

void main() {
  // Checker of u_checker_m squares, box-filtered over the pixel's own footprint (fwidth) so it
  // neither shimmers nor aliases: the integral of the square wave across the pixel, per axis,
  // in units of a square.
  vec2 p = v_world_position.xz;
  vec2 q = p / u_checker_m;
  vec2 w = max(fwidth(q), vec2(1e-4));
  vec2 i = 2.0 * (abs(fract((q - 0.5 * w) * 0.5) - 0.5) - abs(fract((q + 0.5 * w) * 0.5) - 0.5)) / w;
  // Towards the horizon a pixel spans several squares: what is left of the box filter's integral
  // is a ripple of up to 1/w that beats against the pixel grid (moiré). Past two squares per
  // pixel the contrast goes smoothly to the squares' mean, gone at four.
  i *= 1.0 - smoothstep(2.0, 4.0, w);
  float checker = 0.5 - 0.5 * i.x * i.y;
  // Tile colours arrive lit and encoded; mixing them in sRGB is close enough for a filter
  // footprint and saves two pow() per pixel on a CPU rasteriser.
  vec3 color = mix(u_tile_light, u_tile_dark, checker);
  // Fade into the background towards the edge, so the floor has no hard horizon. With a
  // transparent backdrop the floor fades into transparency the same way (premultiplied), so a
  // figure keeps its ground and ends softly on whatever page it is placed.
  vec2 d = p - u_fade_centre;
  float distance = dot(u_fade_axis, u_fade_axis) > 0.0 ? abs(dot(d, u_fade_axis)) : length(d);
  float fade = smoothstep(u_fade_start, u_fade_end, distance);
  if (u_transparent)
    out_color = vec4(color * (1.0 - fade), 1.0 - fade);
  else
    out_color = vec4(mix(color, u_background, fade), 1.0);
}
