#include "mesh_import.hpp"

#include <assimp/BaseImporter.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <system_error>
#include <utility>

#include "confined_io_system.hpp"
#include "format_guard.hpp"
#include "mesh_error.hpp"

namespace tumble {

const std::vector<std::string>& mesh_file_extensions() {
  // The formats users bring (and assimp reads well), not every format assimp knows: each
  // importer is attack surface, and an unknown extension would make assimp try all of them.
  static const std::vector<std::string> extensions = {"obj", "stl", "ply", "off", "gltf",
                                                      "glb", "fbx", "dae", "3ds"};
  return extensions;
}

namespace mesh_detail {
namespace {

namespace fs = std::filesystem;

std::string lower_extension(const fs::path& file) {
  std::string ext = file.extension().string();
  if (!ext.empty() && ext.front() == '.') ext.erase(0, 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string allowed_list() {
  std::string s;
  for (const std::string& e : mesh_file_extensions()) s += (s.empty() ? "." : ", .") + e;
  return s;
}

// Leaves only the importers that claim `extension` registered, so assimp can never fall back
// to trying every importer on the bytes. Owns the importers it takes out (assimp deletes only
// those still registered).
class ImporterRestriction {
 public:
  ImporterRestriction(Assimp::Importer& importer, const std::string& extension) {
    for (std::size_t i = importer.GetImporterCount(); i-- > 0;) {
      Assimp::BaseImporter* loader = importer.GetImporter(i);
      std::set<std::string> extensions;
      loader->GetExtensionList(extensions);
      if (extensions.count(extension) != 0) continue;
      if (importer.UnregisterLoader(loader) == aiReturn_SUCCESS) removed_.emplace_back(loader);
    }
  }

 private:
  std::vector<std::unique_ptr<Assimp::BaseImporter>> removed_;
};

Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  e << m.a1, m.a2, m.a3, m.a4,  //
      m.b1, m.b2, m.b3, m.b4,   //
      m.c1, m.c2, m.c3, m.c4,   //
      m.d1, m.d2, m.d3, m.d4;
  return e;
}

struct MeshInstance {
  const aiMesh* mesh;
  Eigen::Matrix4d transform;  // node to file frame
};

// Every (mesh, accumulated node transform) under the root, depth first in file order. An
// explicit stack: a hostile file cannot overflow the call stack with a deep node tree.
std::vector<MeshInstance> mesh_instances(const aiScene& scene) {
  std::vector<MeshInstance> instances;
  std::vector<std::pair<const aiNode*, Eigen::Matrix4d>> stack;
  stack.emplace_back(scene.mRootNode, to_eigen(scene.mRootNode->mTransformation));
  while (!stack.empty()) {
    auto [node, transform] = stack.back();
    stack.pop_back();
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
      const unsigned index = node->mMeshes[i];
      if (index < scene.mNumMeshes && scene.mMeshes[index] != nullptr)
        instances.push_back({scene.mMeshes[index], transform});
    }
    for (unsigned i = node->mNumChildren; i-- > 0;) {  // reversed: children pop in file order
      const aiNode* child = node->mChildren[i];
      if (child != nullptr)
        stack.emplace_back(child, Eigen::Matrix4d(transform * to_eigen(child->mTransformation)));
    }
  }
  return instances;
}

}  // namespace

TriangleSoup import_triangle_soup(const fs::path& file, const MeshLoadOptions& options) {
  const std::string ext = lower_extension(file);
  const auto& allowed = mesh_file_extensions();
  if (std::find(allowed.begin(), allowed.end(), ext) == allowed.end())
    throw_mesh_error(file, "unsupported mesh format " +
                               (ext.empty() ? std::string("(no extension)") : "\"." + ext + "\"") +
                               ": tumble reads " + allowed_list());

  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) throw_mesh_error(file, "no such mesh file");
  if (!fs::is_regular_file(status)) throw_mesh_error(file, "not a regular file");
  const std::uintmax_t bytes = fs::file_size(file, ec);
  if (ec) throw_mesh_error(file, "cannot read the file: " + ec.message());
  if (bytes > options.max_file_bytes)
    throw_mesh_error(file, "file too large: " + std::to_string(bytes) +
                               " bytes, above the limit of " +
                               std::to_string(options.max_file_bytes));

  if (const std::string why = guard_format(file, ext); !why.empty()) throw_mesh_error(file, why);

  Assimp::Importer importer;
  const ImporterRestriction restriction(importer, ext);
  auto* io = new ConfinedIOSystem(file, options.max_file_bytes);
  importer.SetIOHandler(io);  // the importer owns and deletes it
  // Validate indices and counts first (a garbage file otherwise "loads" as zero meshes). Never
  // JoinIdenticalVertices: it also compares normals and UVs, so flat-shaded files would never
  // weld (we weld by position).
  const aiScene* scene = importer.ReadFile(file.string(), aiProcess_ValidateDataStructure);
  auto fail_read = [&] {
    std::string why = importer.GetErrorString();
    if (!io->refusal().empty()) why = io->refusal() + " (" + why + ")";
    throw_mesh_error(file, "cannot read it as ." + ext + ": " + why);
  };
  if (scene == nullptr) fail_read();
  // assimp 5.2.5 aborts in Triangulate (an assertion) when a mesh's mPrimitiveTypes claims
  // polygons it does not have, which its PLY reader produces from face lines it cannot parse
  // (faces of zero indices, which validation lets through; found by fuzz/fuzz_mesh). Such
  // files are refused, and the types recomputed from the faces before post-processing. The
  // scene is the importer's own, mutable object; only the pointer it hands out is const.
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    aiMesh* mesh = const_cast<aiScene*>(scene)->mMeshes[m];
    if (mesh == nullptr) continue;
    unsigned types = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned n = mesh->mFaces[f].mNumIndices;
      if (n == 0 || mesh->mFaces[f].mIndices == nullptr)
        throw_mesh_error(file, "cannot read it as ." + ext + ": face " + std::to_string(f) +
                                   " has no vertices (the file is corrupt)");
      types |= n == 1   ? aiPrimitiveType_POINT
               : n == 2 ? aiPrimitiveType_LINE
               : n == 3 ? aiPrimitiveType_TRIANGLE
                        : aiPrimitiveType_POLYGON;
    }
    mesh->mPrimitiveTypes = types;
  }
  // Triangulate polygons; GlobalScale applies a file's own unit (FBX).
  scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_GlobalScale);
  if (scene == nullptr) fail_read();
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0 || scene->mRootNode == nullptr)
    throw_mesh_error(file, "the file holds no complete model (an animation or a skeleton only?)");
  if (scene->mNumMeshes == 0) throw_mesh_error(file, "the file holds no meshes");

  const std::vector<MeshInstance> instances = mesh_instances(*scene);
  std::uintmax_t triangle_count = 0, vertex_count = 0;
  for (const MeshInstance& instance : instances) {
    triangle_count += instance.mesh->mNumFaces;
    vertex_count += instance.mesh->mNumVertices;
  }
  if (triangle_count > options.max_triangles)
    throw_mesh_error(file, "too many triangles: " + std::to_string(triangle_count) +
                               ", above the limit of " + std::to_string(options.max_triangles));
  if (vertex_count > std::numeric_limits<std::uint32_t>::max())
    throw_mesh_error(file, "too many vertices: " + std::to_string(vertex_count));

  TriangleSoup soup;
  soup.positions.reserve(static_cast<std::size_t>(vertex_count));
  soup.triangles.reserve(static_cast<std::size_t>(triangle_count));
  for (const MeshInstance& instance : instances) {
    const aiMesh& mesh = *instance.mesh;
    const Mat3 linear = instance.transform.topLeftCorner<3, 3>();
    const Vec3 offset = instance.transform.topRightCorner<3, 1>();
    // A mirroring transform turns an outward winding inward: reverse it back.
    const bool mirrored = linear.determinant() < 0.0;
    const auto base = static_cast<std::uint32_t>(soup.positions.size());
    for (unsigned i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D& v = mesh.mVertices[i];
      const Vec3 p = linear * Vec3(static_cast<double>(v.x), static_cast<double>(v.y),
                                   static_cast<double>(v.z)) +
                     offset;
      soup.positions.push_back(p.cwiseProduct(options.scale));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines bound no volume
      const unsigned a = face.mIndices[0], b = face.mIndices[1], c = face.mIndices[2];
      if (a >= mesh.mNumVertices || b >= mesh.mNumVertices || c >= mesh.mNumVertices)
        throw_mesh_error(file, "a face refers to a vertex that does not exist");
      if (mirrored)
        soup.triangles.push_back({base + a, base + c, base + b});
      else
        soup.triangles.push_back({base + a, base + b, base + c});
    }
  }
  if (soup.triangles.empty())
    throw_mesh_error(file, "the file holds no triangles (points or lines only bound no volume)");
  for (const Vec3& p : soup.positions)
    if (!p.allFinite())
      throw_mesh_error(file, "a vertex coordinate is not a finite number (after scale)");
  return soup;
}

}  // namespace mesh_detail
}  // namespace tumble
