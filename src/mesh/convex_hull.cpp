// The convex hull through Qhull (libqhull_r, the reentrant C library): its default merging of
// nearly coplanar facets keeps the result a valid convex polytope in floating point, so a
// cube's hull is 8 vertices and 6 faces, not 12 slightly bent triangles.
#include <libqhull_r/qhull_ra.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numeric>
#include <string>
#include <tuple>

#include "tumble/error.hpp"
#include "tumble/mesh.hpp"

namespace tumble {
namespace {

// Qhull's messages land in a memory stream, read once Qhull is done with it.
class MessageStream {
 public:
  MessageStream() : file_(open_memstream(&buffer_, &size_)) {}
  ~MessageStream() {
    close();
    std::free(buffer_);
  }
  MessageStream(const MessageStream&) = delete;
  MessageStream& operator=(const MessageStream&) = delete;
  FILE* file() const { return file_; }
  /// The first line Qhull wrote (its error code and summary), without the help that follows.
  std::string first_line() {
    close();
    if (buffer_ == nullptr) return "";
    std::string text(buffer_, size_);
    const std::size_t start = text.find_first_not_of(" \n");
    if (start == std::string::npos) return "";
    const std::size_t end = text.find('\n', start);
    return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
  }

 private:
  void close() {
    if (file_ != nullptr) std::fclose(file_);
    file_ = nullptr;
  }
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_ = nullptr;
};

// One Qhull computation's state, freed whatever happens.
class QhullRun {
 public:
  explicit QhullRun(FILE* errors) : qh_(std::make_unique<qhT>()) { qh_zero(qh_.get(), errors); }
  ~QhullRun() {
    qh_freeqhull(qh_.get(), !qh_ALL);
    int still_long = 0, total_long = 0;
    qh_memfreeshort(qh_.get(), &still_long, &total_long);
  }
  QhullRun(const QhullRun&) = delete;
  QhullRun& operator=(const QhullRun&) = delete;
  qhT* get() const { return qh_.get(); }

 private:
  std::unique_ptr<qhT> qh_;
};

// The elements of a Qhull set (NULL-terminated array of pointers).
template <typename T>
std::vector<T*> set_elements(setT* set) {
  std::vector<T*> out;
  if (set == nullptr) return out;
  const setelemT* e = set->e;
  for (std::size_t i = 0; e[i].p != nullptr; ++i) out.push_back(static_cast<T*>(e[i].p));
  return out;
}

bool lexicographic_less(const Vec3& a, const Vec3& b) {
  return std::tie(a.x(), a.y(), a.z()) < std::tie(b.x(), b.y(), b.z());
}

}  // namespace

ConvexHull convex_hull(const std::vector<Vec3>& points) {
  if (points.size() < 4)
    throw Error(ErrorKind::BadInput, "flat: " + std::to_string(points.size()) +
                                         " points span no volume (a hull needs 4 or more)");
  for (const Vec3& p : points)
    if (!p.allFinite()) throw Error(ErrorKind::BadInput, "a point is not finite");
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * points.size());
  for (const Vec3& p : points) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});

  MessageStream messages;
  QhullRun run(messages.file());
  qhT* qh = run.get();
  char command[] = "qhull";  // defaults: facets merged within Qhull's round-off estimate
  const int status = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False,
                                  command, nullptr, messages.file());
  if (status == qh_ERRsingular)
    throw Error(ErrorKind::BadInput,
                "flat: the points lie in one plane or on one line, to "
                "Qhull's precision (" +
                    messages.first_line() + ")");
  if (status != 0)
    throw Error(ErrorKind::BadInput, "the convex hull failed: " + messages.first_line());

  // Each facet: its vertices ordered around its outward normal, fanned into triangles. The
  // order comes from angles in the facet's plane rather than Qhull's ridge walk, so nothing
  // after qh_new_qhull can reach Qhull's error exit.
  const coordT* first = qh->first_point;
  std::vector<std::vector<std::uint32_t>> polygons;
  for (facetT* facet = qh->facet_list; facet != nullptr && facet->next != nullptr;
       facet = facet->next) {
    if (facet->visible) continue;
    const Vec3 normal(facet->normal[0], facet->normal[1], facet->normal[2]);
    std::vector<std::uint32_t> ids;
    for (vertexT* vertex : set_elements<vertexT>(facet->vertices)) {
      const std::ptrdiff_t offset = vertex->point - first;
      if (offset < 0 || offset % 3 != 0 || static_cast<std::size_t>(offset / 3) >= points.size())
        throw Error(ErrorKind::BadInput, "the convex hull failed: a vertex outside the input");
      ids.push_back(static_cast<std::uint32_t>(offset / 3));
    }
    if (ids.size() < 3) continue;
    Vec3 centre = Vec3::Zero();
    for (std::uint32_t id : ids) centre += points[id];
    centre /= static_cast<double>(ids.size());
    const Vec3 u = (points[ids[0]] - centre).normalized();
    const Vec3 v = normal.cross(u);
    std::vector<std::pair<double, std::uint32_t>> around;
    for (std::uint32_t id : ids) {
      const Vec3 r = points[id] - centre;
      around.emplace_back(std::atan2(r.dot(v), r.dot(u)), id);
    }
    std::sort(around.begin(), around.end());  // counter-clockwise about the outward normal
    std::vector<std::uint32_t> polygon;
    for (const auto& [angle, id] : around) polygon.push_back(id);
    polygons.push_back(std::move(polygon));
  }

  // Vertices sorted by (x, y, z): the same hull whatever order the points came in.
  std::vector<std::uint32_t> used;
  for (const auto& polygon : polygons) used.insert(used.end(), polygon.begin(), polygon.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::stable_sort(used.begin(), used.end(), [&](std::uint32_t a, std::uint32_t b) {
    return lexicographic_less(points[a], points[b]);
  });
  std::vector<std::uint32_t> new_index(points.size(), 0);
  ConvexHull hull;
  for (std::uint32_t id : used) {
    new_index[id] = static_cast<std::uint32_t>(hull.mesh.vertices.size());
    hull.mesh.vertices.push_back(points[id]);
  }
  // Faces in a canonical order too: each rotated to start at its smallest vertex, then sorted.
  for (auto& polygon : polygons) {
    for (std::uint32_t& id : polygon) id = new_index[id];
    std::rotate(polygon.begin(), std::min_element(polygon.begin(), polygon.end()), polygon.end());
  }
  std::sort(polygons.begin(), polygons.end());
  hull.faces = polygons.size();
  for (const auto& polygon : polygons)
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
      hull.mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
  return hull;
}

std::vector<Vec3> convex_hull_vertices(const std::vector<Vec3>& points) {
  return convex_hull(points).mesh.vertices;
}

}  // namespace tumble
