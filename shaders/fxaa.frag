// FXAA (after Timothy Lottes' FXAA 3.11 "console" variant): finds the local edge direction from
// the luma of the four diagonal neighbours and blends along it. One full-screen pass: on a CPU
// rasteriser it costs a fraction of what 4x MSAA does, and smooths the bodies' silhouettes and
// shadow edges (the floor checker is already filtered analytically in floor.frag).
in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_pixel;  // 1 / size

out vec4 out_color;

const vec3 kLuma = vec3(0.299, 0.587, 0.114);

void main() {
  // Unfiltered fetches for the neighbourhood (filtering is what costs on a CPU rasteriser);
  // the clamp keeps the border pixels' neighbours inside the image.
  ivec2 c = ivec2(gl_FragCoord.xy);
  ivec2 hi = textureSize(u_image, 0) - 1;
  vec3 m = texelFetch(u_image, c, 0).rgb;
  float lm = dot(m, kLuma);
  float lnw = dot(texelFetch(u_image, clamp(c + ivec2(-1, -1), ivec2(0), hi), 0).rgb, kLuma);
  float lne = dot(texelFetch(u_image, clamp(c + ivec2(1, -1), ivec2(0), hi), 0).rgb, kLuma);
  float lsw = dot(texelFetch(u_image, clamp(c + ivec2(-1, 1), ivec2(0), hi), 0).rgb, kLuma);
  float lse = dot(texelFetch(u_image, clamp(c + ivec2(1, 1), ivec2(0), hi), 0).rgb, kLuma);
  float lmin = min(lm, min(min(lnw, lne), min(lsw, lse)));
  float lmax = max(lm, max(max(lnw, lne), max(lsw, lse)));
  // Flat neighbourhood: nothing to smooth (most pixels; keeps them bit-exact).
  if (lmax - lmin < max(0.0312, lmax * 0.125)) {
    out_color = vec4(m, 1.0);
    return;
  }
  vec2 dir = vec2(-((lnw + lne) - (lsw + lse)), (lnw + lsw) - (lne + lse));
  float reduce = max((lnw + lne + lsw + lse) * (0.25 / 8.0), 1.0 / 128.0);
  float scale = 1.0 / (min(abs(dir.x), abs(dir.y)) + reduce);
  dir = clamp(dir * scale, vec2(-8.0), vec2(8.0)) * u_pixel;
  vec3 a = 0.5 * (texture(u_image, v_uv + dir * (1.0 / 3.0 - 0.5)).rgb +
                  texture(u_image, v_uv + dir * (2.0 / 3.0 - 0.5)).rgb);
  vec3 b = 0.5 * a + 0.25 * (texture(u_image, v_uv - 0.5 * dir).rgb +
                             texture(u_image, v_uv + 0.5 * dir).rgb);
  float lb = dot(b, kLuma);
  out_color = vec4((lb < lmin || lb > lmax) ? a : b, 1.0);
}
