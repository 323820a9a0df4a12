// FXAA (after Timothy Lottes' FXAA 3.11 "console" variant): finds the local edge direction from
// the luma of the four diagonal neighbours and blends along it. One full-screen pass: on a CPU
// rasteriser it costs a fraction of what 4x MSAA does, and smooths the bodies' silhouettes and
// shadow edges (the floor checker is already filtered analytically in floor.frag).
in vec2 v_uv;

uniform sampler2D u_image;
uniform vec2 u_pixel;  // 1 / size
// Transparent backdrop: colours are premultiplied and all four channels are blended, so an edge
// is smoothed against transparency (straight alpha after readback), not against a sky colour.
uniform bool u_alpha;

out vec4 out_color;

const vec3 kLuma = vec3(0.299, 0.587, 0.114);

float luma(vec4 c, bool alpha_edge) {
  return alpha_edge ? c.a : dot(c.rgb, kLuma);
}

void main() {
  // Unfiltered fetches for the neighbourhood (filtering is what costs on a CPU rasteriser);
  // the clamp keeps the border pixels' neighbours inside the image.
  ivec2 c = ivec2(gl_FragCoord.xy);
  ivec2 hi = textureSize(u_image, 0) - 1;
  vec4 m = texelFetch(u_image, c, 0);
  vec4 nw = texelFetch(u_image, clamp(c + ivec2(-1, -1), ivec2(0), hi), 0);
  vec4 ne = texelFetch(u_image, clamp(c + ivec2(1, -1), ivec2(0), hi), 0);
  vec4 sw = texelFetch(u_image, clamp(c + ivec2(-1, 1), ivec2(0), hi), 0);
  vec4 se = texelFetch(u_image, clamp(c + ivec2(1, 1), ivec2(0), hi), 0);
  // Which channel shows the edge: luma, or alpha where alpha varies more (a silhouette against
  // the transparent background, whose luma may match the body's: a dark body on nothing).
  bool alpha_edge = false;
  if (u_alpha) {
    float amin = min(m.a, min(min(nw.a, ne.a), min(sw.a, se.a)));
    float amax = max(m.a, max(max(nw.a, ne.a), max(sw.a, se.a)));
    float l0 = dot(m.rgb, kLuma), l1 = dot(nw.rgb, kLuma), l2 = dot(ne.rgb, kLuma);
    float l3 = dot(sw.rgb, kLuma), l4 = dot(se.rgb, kLuma);
    float lrange = max(l0, max(max(l1, l2), max(l3, l4))) - min(l0, min(min(l1, l2), min(l3, l4)));
    alpha_edge = amax - amin > lrange;
  }
  float lm = luma(m, alpha_edge);
  float lnw = luma(nw, alpha_edge);
  float lne = luma(ne, alpha_edge);
  float lsw = luma(sw, alpha_edge);
  float lse = luma(se, alpha_edge);
  float lmin = min(lm, min(min(lnw, lne), min(lsw, lse)));
  float lmax = max(lm, max(max(lnw, lne), max(lsw, lse)));
  // Flat neighbourhood: nothing to smooth (most pixels; keeps them bit-exact).
  if (lmax - lmin < max(0.0312, lmax * 0.125)) {
    out_color = u_alpha ? m : vec4(m.rgb, 1.0);
    return;
  }
  vec2 dir = vec2(-((lnw + lne) - (lsw + lse)), (lnw + lsw) - (lne + lse));
  float reduce = max((lnw + lne + lsw + lse) * (0.25 / 8.0), 1.0 / 128.0);
  float scale = 1.0 / (min(abs(dir.x), abs(dir.y)) + reduce);
  dir = clamp(dir * scale, vec2(-8.0), vec2(8.0)) * u_pixel;
  vec4 a = 0.5 * (texture(u_image, v_uv + dir * (1.0 / 3.0 - 0.5)) +
                  texture(u_image, v_uv + dir * (2.0 / 3.0 - 0.5)));
  vec4 b = 0.5 * a + 0.25 * (texture(u_image, v_uv - 0.5 * dir) +
                             texture(u_image, v_uv + 0.5 * dir));
  float lb = luma(b, alpha_edge);
  vec4 result = (lb < lmin || lb > lmax) ? a : b;
  out_color = u_alpha ? result : vec4(result.rgb, 1.0);
}
