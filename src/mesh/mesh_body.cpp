// load_mesh_body: file -> triangle soup -> welded mesh -> topology verdicts (or repairs) ->
// orientation of every shell -> mass properties, convex hull and the checks that tie them.
// Nothing half-checked leaves this function: it returns a valid body or throws.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "edge_topology.hpp"
#include "mesh_error.hpp"
#include "mesh_import.hpp"
#include "shell_orientation.hpp"
#include "solid_checks.hpp"
#include "tumble/error.hpp"
#include "tumble/mesh.hpp"
#include "vertex_weld.hpp"

namespace tumble {
namespace {

using namespace mesh_detail;
namespace fs = std::filesystem;

// Coordinates beyond this cannot be integrated (the inertia sums fifth powers) and are no
// rigid body tumble can show.
constexpr double kMaxCoordinate = 1e30;

struct Welded {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;  // collapsed ones removed; slivers kept
  std::vector<bool> sliver;         // per triangle: zero area (height below the weld tolerance)
  std::vector<std::uint32_t> source;  // per triangle: its triangle in the soup
  std::size_t collapsed = 0;        // triangles removed because two corners welded together
  std::size_t used_vertices = 0;
  double tolerance = 0;
};

Welded weld_soup(const TriangleSoup& soup, Weld& weld) {
  weld = weld_vertices(soup.positions);
  Welded w;
  w.vertices = weld.vertices;
  w.tolerance = weld.tolerance;
  std::vector<bool> used(w.vertices.size(), false);
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const auto& t = soup.triangles[f];
    const Triangle m{weld.index_of[t[0]], weld.index_of[t[1]], weld.index_of[t[2]]};
    if (m[0] == m[1] || m[1] == m[2] || m[2] == m[0]) {
      ++w.collapsed;
      continue;
    }
    w.source.push_back(static_cast<std::uint32_t>(f));
    const Vec3 &a = w.vertices[m[0]], &b = w.vertices[m[1]], &c = w.vertices[m[2]];
    const double twice_area = (b - a).cross(c - a).norm();
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    // Height over the longest edge below the weld tolerance: a zero-area sliver. It still
    // joins its edges (T-junctions close through it) but is not drawn.
    w.sliver.push_back(twice_area <= w.tolerance * longest);
    w.triangles.push_back(m);
    for (std::uint32_t v : m) used[v] = true;
  }
  w.used_vertices = static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
  return w;
}

// The triangles kept by `keep` with only the vertices they use, in first-use order; `kept`, when
// given, receives the index of each kept triangle.
template <typename Keep>
TriangleMesh compact_mesh(const std::vector<Vec3>& vertices, const std::vector<Triangle>& triangles,
                          Keep keep, std::vector<std::uint32_t>* kept = nullptr) {
  TriangleMesh mesh;
  std::vector<std::uint32_t> index(vertices.size(), UINT32_MAX);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    if (!keep(f)) continue;
    std::array<std::uint32_t, 3> t{};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = triangles[f][k];
      if (index[v] == UINT32_MAX) {
        index[v] = static_cast<std::uint32_t>(mesh.vertices.size());
        mesh.vertices.push_back(vertices[v]);
      }
      t[k] = index[v];
    }
    mesh.triangles.push_back(t);
    if (kept != nullptr) kept->push_back(static_cast<std::uint32_t>(f));
  }
  return mesh;
}

// The soup's appearance carried over to the drawn triangles: `kept` names each drawn triangle's
// welded triangle, whose corners may have been re-wound (1 and 2 swapped), so each corner takes
// the attributes of the soup corner that welded to the same vertex.
MeshAppearance carry_appearance(const TriangleSoup& soup, const Weld& weld, const Welded& w,
                                const std::vector<Triangle>& wound,
                                const std::vector<std::uint32_t>& kept) {
  MeshAppearance out;
  const MeshAppearance& in = soup.appearance;
  if (!in.has_materials()) return out;
  out.materials = in.materials;
  out.textures = in.textures;
  for (const std::uint32_t f : kept) {
    const std::uint32_t s = w.source[f];
    const auto& corners = soup.triangles[s];
    std::array<Vec3, 3> color;
    std::array<Eigen::Vector2d, 3> uv;
    for (std::size_t k = 0; k < 3; ++k) {
      std::size_t j = 0;
      while (j < 2 && weld.index_of[corners[j]] != wound[f][k]) ++j;
      color[k] = in.corner_color[s][j];
      uv[k] = in.corner_uv[s][j];
    }
    out.triangle_material.push_back(in.triangle_material[s]);
    out.corner_color.push_back(color);
    out.corner_uv.push_back(uv);
  }
  return out;
}

class Reporter {
 public:
  Reporter(const fs::path& file, const Vec3& scale, const std::vector<Vec3>& vertices)
      : file_(file), scale_(scale), vertices_(vertices) {}

  /// A point in the file's units (before `scale`): what a modelling program shows.
  std::string point(const Vec3& p) const { return format_point(p.cwiseQuotient(scale_)); }
  std::string edges(const std::vector<Edge>& examples) const {
    std::string s;
    for (const Edge& e : examples)
      s += (s.empty() ? "" : ", ") + point(vertices_[e[0]]) + "\u2013" + point(vertices_[e[1]]);
    return s;
  }
  [[noreturn]] void fail(const std::string& message) const { throw_mesh_error(file_, message); }
  const fs::path& file() const { return file_; }

 private:
  const fs::path& file_;
  Vec3 scale_;
  const std::vector<Vec3>& vertices_;
};

// The topology problems of a census, in the order a user should fix them.
std::vector<std::string> edge_problems(const EdgeCensus& census, const Reporter& report,
                                       bool winding) {
  std::vector<std::string> problems;
  if (census.open > 0)
    problems.push_back("not closed: " + count_of(census.open, "open edge", "open edges") +
                       " (used by one triangle only), e.g. " + report.edges(census.open_examples));
  if (census.non_manifold > 0)
    problems.push_back("non-manifold: " + count_of(census.non_manifold, "edge is", "edges are") +
                       " shared by more than two triangles, e.g. " +
                       report.edges(census.non_manifold_examples));
  if (winding && census.misoriented > 0)
    problems.push_back(
        "inconsistent winding: " + count_of(census.misoriented, "edge is", "edges are") +
        " used twice in the same direction (neighbouring triangles face opposite "
        "ways), e.g. " +
        report.edges(census.misoriented_examples));
  return problems;
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string s;
  for (const std::string& p : parts) s += (s.empty() ? "" : separator) + p;
  return s;
}

ConvexHull hull_of(const Reporter& report, const std::vector<Vec3>& points,
                   const std::string& prefix) {
  try {
    return convex_hull(points);
  } catch (const Error& e) {
    report.fail(prefix + e.what());
  }
}

MeshBody hull_body(const Welded& w, const Reporter& report, std::size_t source_triangles) {
  const TriangleMesh surface =
      compact_mesh(w.vertices, w.triangles, [](std::size_t) { return true; });
  const ConvexHull hull = hull_of(report, surface.vertices, "repair = \"hull\": ");
  MeshBody body;
  // Drawn without fan triangles of zero area (a hull face's vertices nearly in line).
  body.mesh = compact_mesh(hull.mesh.vertices, hull.mesh.triangles, [&](std::size_t f) {
    const auto& t = hull.mesh.triangles[f];
    const Vec3 &a = hull.mesh.vertices[t[0]], &b = hull.mesh.vertices[t[1]],
               &c = hull.mesh.vertices[t[2]];
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    return (b - a).cross(c - a).norm() > w.tolerance * longest;
  });
  body.mass = mass_properties(hull.mesh);
  check_solid(report.file(), measure_surface(hull.mesh), body.mass, body.mass.volume,
              "its convex hull");
  body.hull_vertices = hull.mesh.vertices;
  body.hull_faces = hull.faces;
  body.repair_note = "replaced by its convex hull (" +
                     count_of(hull.mesh.vertices.size(), "vertex", "vertices") + ", " +
                     count_of(hull.faces, "face", "faces") + ") in place of the " +
                     count_of(source_triangles, "source triangle", "source triangles");
  // What was wrong with the source, in short, for run.json.
  const EdgeCensus census = census_edges(w.triangles);
  std::vector<std::string> defects;
  if (census.open > 0)
    defects.push_back("not closed (" + count_of(census.open, "open edge", "open edges") + ")");
  if (census.non_manifold > 0)
    defects.push_back("non-manifold (" + count_of(census.non_manifold, "edge", "edges") + ")");
  if (census.misoriented > 0)
    defects.push_back("inconsistently wound (" + count_of(census.misoriented, "edge", "edges") +
                      ")");
  if (!defects.empty()) body.repair_note += ", which were " + join(defects, ", ");
  return body;
}

}  // namespace

MeshBody load_mesh_body(const fs::path& file, const MeshLoadOptions& options) {
  if (!options.scale.allFinite() || !(options.scale.minCoeff() > 0.0))
    throw_mesh_error(file, "scale must be finite and positive on every axis, got " +
                               format_point(options.scale));
  const TriangleSoup soup = import_triangle_soup(file, options);
  for (const Vec3& p : soup.positions)
    if (p.cwiseAbs().maxCoeff() > kMaxCoordinate)
      throw_mesh_error(file, "a vertex lies beyond 1e30 m of the origin (after scale)");

  Weld weld;
  const Welded w = weld_soup(soup, weld);
  const Reporter report(file, options.scale, w.vertices);
  const std::size_t source_triangles = soup.triangles.size();
  const auto slivers = static_cast<std::size_t>(std::count(w.sliver.begin(), w.sliver.end(), true));
  const std::size_t degenerate = w.collapsed + slivers;
  // A few zero-area triangles are what exporters leave behind; a surface that is mostly made of
  // them is not a model.
  if (4 * degenerate > source_triangles) {
    std::string example;
    for (std::size_t f = 0; f < w.triangles.size() && example.empty(); ++f)
      if (w.sliver[f]) example = ", e.g. at " + report.point(w.vertices[w.triangles[f][0]]);
    report.fail("degenerate: " + std::to_string(degenerate) + " of " +
                count_of(source_triangles, "triangle has", "triangles have") +
                " zero area (corners closer than " + format_number(w.tolerance) +
                " m to each other or to a line)" + example);
  }

  MeshBody body;
  body.source_triangles = source_triangles;
  body.welded_vertices = w.used_vertices;
  body.degenerate_triangles = degenerate;
  if (options.repair == MeshRepair::Hull) {
    MeshBody hull = hull_body(w, report, source_triangles);
    hull.source_triangles = source_triangles;
    hull.welded_vertices = w.used_vertices;
    hull.degenerate_triangles = degenerate;
    return hull;
  }

  // Topology: every edge in exactly two triangles, once in each direction.
  Welded fixed = w;
  std::vector<std::string> notes;
  const EdgeCensus census = census_edges(w.triangles);
  const bool orient = options.repair == MeshRepair::Orient;
  if (std::vector<std::string> problems = edge_problems(census, report, !orient);
      !problems.empty()) {
    std::string hint;
    if (!census.closed_manifold())
      hint = " (repair = \"hull\" would use its convex hull instead)";
    else
      hint = " (repair = \"orient\" makes the winding consistent)";
    report.fail(join(problems, "; ") + hint);
  }
  if (census.misoriented > 0) {
    const std::vector<bool> flips = consistent_flips(fixed.triangles);
    if (flips.empty())
      report.fail(
          "not orientable: no winding makes every edge run once each way (a surface "
          "like a Klein bottle bounds no solid)");
    std::size_t flipped = 0;
    for (std::size_t f = 0; f < flips.size(); ++f)
      if (flips[f]) {
        std::swap(fixed.triangles[f][1], fixed.triangles[f][2]);
        ++flipped;
      }
    notes.push_back("re-wound " + count_of(flipped, "triangle", "triangles") +
                    " to match their neighbours");
  }

  // Orientation of each shell: outward, or inward around a cavity.
  const auto all = [](std::size_t) { return true; };
  TriangleMesh closed = compact_mesh(fixed.vertices, fixed.triangles, all);
  const SurfaceMeasures surface = measure_surface(closed);
  const std::vector<Shell> shells = orient_shells(fixed.vertices, fixed.triangles);
  for (const Shell& shell : shells)
    if (!(std::abs(shell.signed_volume) > surface.zero_volume()))
      report.fail("zero volume: " +
                  (shells.size() == 1
                       ? std::string("the surface")
                       : "a shell of " + count_of(shell.triangles.size(), "triangle", "triangles") +
                             " at " + report.point(shell.example)) +
                  " encloses no volume (" + format_number(shell.signed_volume) +
                  " m^3: it is flat, or two copies of one surface facing opposite ways)");
  for (const Shell& shell : shells)
    if (shell.crosses)
      report.fail("self-intersecting: the shell of " +
                  count_of(shell.triangles.size(), "triangle", "triangles") + " at " +
                  report.point(shell.example) + " crosses another shell of the mesh");
  std::size_t wrong = 0, wrong_triangles = 0;
  const Shell* first_wrong = nullptr;
  for (const Shell& shell : shells)
    if (shell.inside_out) {
      ++wrong;
      wrong_triangles += shell.triangles.size();
      if (first_wrong == nullptr) first_wrong = &shell;
    }
  if (wrong > 0) {
    if (options.repair == MeshRepair::None) {
      if (shells.size() == 1)
        report.fail("inside-out: its " +
                    count_of(wrong_triangles, "triangle faces", "triangles face") +
                    " inward (signed volume " + format_number(first_wrong->signed_volume) +
                    " m^3); repair = \"orient\" flips them");
      report.fail("inside-out: " + std::to_string(wrong) + " of " + std::to_string(shells.size()) +
                  " shells face the wrong way (an outer shell must face outward, a cavity's "
                  "inward), e.g. the shell of " +
                  count_of(first_wrong->triangles.size(), "triangle", "triangles") + " at " +
                  report.point(first_wrong->example) + "; repair = \"orient\" flips them");
    }
    for (const Shell& shell : shells)
      if (shell.inside_out)
        for (std::uint32_t f : shell.triangles)
          std::swap(fixed.triangles[f][1], fixed.triangles[f][2]);
    notes.push_back("flipped " + count_of(wrong_triangles, "triangle", "triangles") +
                    (shells.size() == 1
                         ? std::string(" (the mesh was inside-out)")
                         : " in " + count_of(wrong, "inside-out shell", "inside-out shells")));
    closed = compact_mesh(fixed.vertices, fixed.triangles, all);
  }

  // Mass properties of the closed surface (slivers included: they close T-junctions and weigh
  // nothing), its hull, and the checks between them.
  body.mass = mass_properties(closed);
  std::vector<std::uint32_t> drawn;
  body.mesh = compact_mesh(
      fixed.vertices, fixed.triangles, [&](std::size_t f) { return !fixed.sliver[f]; }, &drawn);
  body.appearance = carry_appearance(soup, weld, w, fixed.triangles, drawn);
  const ConvexHull hull = hull_of(report, body.mesh.vertices, "");
  const MassProperties hull_mass = mass_properties(hull.mesh);
  check_solid(file, surface, body.mass, hull_mass.volume, "the mesh");
  body.hull_vertices = hull.mesh.vertices;
  body.hull_faces = hull.faces;
  body.repair_note = join(notes, "; ");
  return body;
}

}  // namespace tumble
