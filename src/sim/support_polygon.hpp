#pragma once
// The support polygon of contact points seen along the floor normal: their 2-D convex hull in
// the floor plane (x, z), and whether a point lies strictly inside it. Used to reduce a hull
// face's many contact points, to accept the resting-face wrench, and for static equilibrium.
// Works in caller-provided buffers: no allocation inside a step.

namespace tumble {

/// A point in the floor plane, and which contact vertex it came from.
struct PlanePoint {
  double x = 0.0, z = 0.0;
  int index = 0;
};

/// Writes the corners of the convex hull of points[0, n) to `hull` (room for 2n + 1) counter-
/// clockwise, by Andrew's monotone chain, and returns their number: collinear and repeated
/// points dropped, ties broken by index (deterministic). Fewer than 3 when the points span no
/// area. Sorts `points` in place.
int support_polygon(PlanePoint* points, int n, PlanePoint* hull);

/// True when (x, z) lies inside the polygon of `n` counter-clockwise corners farther than
/// `margin` × the edge length from every edge. False for fewer than 3 corners.
bool strictly_inside(const PlanePoint* polygon, int n, double x, double z, double margin);

}  // namespace tumble
