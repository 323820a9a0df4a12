#include "mesh_import.hpp"

#include <assimp/BaseImporter.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <limits>
#include <memory>
#include <set>
#include <string>
#include <system_error>
#include <utility>

#include "confined_io_system.hpp"
#include "format_guard.hpp"
#include "mesh_error.hpp"
#include "texture_decode.hpp"

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

double srgb_to_linear(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

Vec3 to_linear(const aiColor4D& c, bool linear) {
  const Vec3 v(static_cast<double>(c.r), static_cast<double>(c.g), static_cast<double>(c.b));
  if (linear) return v.cwiseMax(0.0).cwiseMin(1.0);
  return {srgb_to_linear(v.x()), srgb_to_linear(v.y()), srgb_to_linear(v.z())};
}

// A model's materials as tumble draws them: which of assimp's materials are the file's own
// (assimp invents a default one for files that have none), their colours in linear RGB and
// their textures, each decoded once.
class MaterialTable {
 public:
  MaterialTable(const aiScene& scene, const fs::path& file, const std::string& ext,
                ConfinedIOSystem& io, const MeshLoadOptions& options)
      : scene_(scene), file_(file), io_(io), options_(options) {
    // glTF defines its factors and vertex colours as linear; the other formats' colours are
    // what their authors picked on screen (like the scene's `color`): sRGB.
    linear_ = ext == "gltf" || ext == "glb";
    for (unsigned i = 0; i < scene.mNumMaterials; ++i) {
      const aiMaterial* m = scene.mMaterials[i];
      entries_.push_back(m != nullptr && own(*m, i, ext) ? read(*m) : Entry{});
    }
  }

  bool linear_colors() const { return linear_; }
  /// The material of aiMesh material index i: the body's colour where it is not the file's,
  /// except under vertex colours, which are shown as they are (white, as glTF's default).
  std::uint32_t material_of(unsigned i, bool vertex_colors) {
    if (i < entries_.size() && entries_[i].own) return entries_[i].index;
    if (!vertex_colors) return kBodyColor;
    if (white_ == kBodyColor) {
      white_ = static_cast<std::uint32_t>(materials_.size());
      materials_.push_back(MeshMaterial{});
    }
    return white_;
  }
  unsigned uv_channel_of(unsigned i) const { return i < entries_.size() ? entries_[i].uv : 0; }
  bool any_own() const {
    return std::any_of(entries_.begin(), entries_.end(), [](const Entry& e) { return e.own; });
  }
  /// Moves the materials and textures into `appearance`, with the body-colour material at
  /// index kBodyColor replaced by its real index.
  void finish(MeshAppearance& appearance) {
    MeshMaterial body;
    body.use_body_color = true;
    const auto body_index = static_cast<std::uint32_t>(materials_.size());
    materials_.push_back(body);
    for (std::uint32_t& t : appearance.triangle_material)
      if (t == kBodyColor) t = body_index;
    appearance.materials = std::move(materials_);
    appearance.textures = std::move(textures_);
  }

  static constexpr std::uint32_t kBodyColor = UINT32_MAX;

 private:
  struct Entry {
    bool own = false;
    std::uint32_t index = 0;  // into materials_
    unsigned uv = 0;          // texture coordinate channel of its texture
  };

  bool own(const aiMaterial& m, unsigned index, const std::string& ext) const {
    aiString name;
    m.Get(AI_MATKEY_NAME, name);
    const std::string n = name.C_Str();
    if (ext == "gltf" || ext == "glb")  // assimp appends its default material last
      return index + 1 < scene_.mNumMaterials;
    if (ext == "stl" || ext == "ply" || ext == "off") return false;  // no materials in these
    // An OBJ's materials come from its .mtl: without one, `usemtl` names only invent defaults.
    if (ext == "obj" && !io_.opened_with_extension(".mtl")) return false;
    return n != AI_DEFAULT_MATERIAL_NAME;
  }

  Entry read(const aiMaterial& m) {
    MeshMaterial out;
    aiString name;
    m.Get(AI_MATKEY_NAME, name);
    out.name = name.C_Str();
    aiColor4D color(1.0f, 1.0f, 1.0f, 1.0f);
    if (m.Get(AI_MATKEY_BASE_COLOR, color) != AI_SUCCESS) m.Get(AI_MATKEY_COLOR_DIFFUSE, color);
    out.base_color_linear = to_linear(color, linear_);
    Entry e;
    for (const aiTextureType type : {aiTextureType_BASE_COLOR, aiTextureType_DIFFUSE}) {
      aiString path;
      if (m.GetTextureCount(type) == 0 || m.GetTexture(type, 0, &path) != AI_SUCCESS) continue;
      out.texture = texture(path.C_Str());
      int channel = 0;
      if (m.Get(AI_MATKEY_UVWSRC(type, 0), channel) == AI_SUCCESS && channel > 0 &&
          channel < int(AI_MAX_NUMBER_OF_TEXTURECOORDS))
        e.uv = unsigned(channel);
      break;
    }
    e.own = true;
    e.index = static_cast<std::uint32_t>(materials_.size());
    materials_.push_back(out);
    return e;
  }

  // The texture `reference` names, decoded (once per name): embedded ("*N", a glTF buffer view
  // or data URI) or a file relative to the model's folder.
  int texture(const std::string& reference) {
    if (auto it = by_name_.find(reference); it != by_name_.end()) return it->second;
    TextureImage image;
    const auto [embedded, embedded_index] = scene_.GetEmbeddedTextureAndIndex(reference.c_str());
    if (embedded != nullptr) {
      image = decode_embedded(*embedded, embedded_index);
    } else {
      std::string relative = reference;
      std::replace(relative.begin(), relative.end(), '\\', '/');  // written on Windows
      const fs::path path = fs::path(relative).is_absolute()
                                ? fs::path(relative)
                                : file_.parent_path() / fs::path(relative);
      std::vector<std::uint8_t> bytes;
      std::string why;
      if (!io_.read_whole(path, bytes, why)) fail_texture(path.string(), why);
      if (bytes.size() > options_.max_file_bytes)
        fail_texture(path.string(), "file too large: " + std::to_string(bytes.size()) +
                                        " bytes, above the limit of " +
                                        std::to_string(options_.max_file_bytes));
      DecodedTexture decoded = decode_texture(bytes, options_.max_texture_pixels);
      if (!decoded.why.empty()) fail_texture(path.string(), decoded.why);
      image = std::move(decoded.image);
      image.source = path.string();
    }
    const int index = static_cast<int>(textures_.size());
    textures_.push_back(std::move(image));
    by_name_.emplace(reference, index);
    return index;
  }

  TextureImage decode_embedded(const aiTexture& t, int index) {
    const std::string source = file_.string() + ", embedded texture " + std::to_string(index);
    if (t.mHeight == 0) {  // compressed: mWidth bytes of a PNG, JPEG, ...
      const auto* data = reinterpret_cast<const std::uint8_t*>(t.pcData);
      DecodedTexture decoded = decode_texture(std::span<const std::uint8_t>(data, t.mWidth),
                                              options_.max_texture_pixels);
      if (!decoded.why.empty()) fail_texture(source, decoded.why);
      decoded.image.source = source;
      return std::move(decoded.image);
    }
    // Raw BGRA texels (formats that store uncompressed images).
    if (std::uint64_t(t.mWidth) * t.mHeight > options_.max_texture_pixels)
      fail_texture(source, "too large");
    TextureImage image;
    image.width = int(t.mWidth);
    image.height = int(t.mHeight);
    image.source = source;
    image.rgba.resize(std::size_t(t.mWidth) * t.mHeight * 4);
    for (std::size_t i = 0; i < std::size_t(t.mWidth) * t.mHeight; ++i) {
      const aiTexel& p = t.pcData[i];
      image.rgba[4 * i + 0] = p.r;
      image.rgba[4 * i + 1] = p.g;
      image.rgba[4 * i + 2] = p.b;
      image.rgba[4 * i + 3] = p.a;
    }
    return image;
  }

  [[noreturn]] void fail_texture(const std::string& texture, const std::string& why) const {
    throw_mesh_error(file_, "texture \"" + texture + "\": " + why);
  }

  const aiScene& scene_;
  const fs::path& file_;
  ConfinedIOSystem& io_;
  const MeshLoadOptions& options_;
  bool linear_ = false;
  std::vector<Entry> entries_;
  std::vector<MeshMaterial> materials_;
  std::vector<TextureImage> textures_;
  std::map<std::string, int> by_name_;
  std::uint32_t white_ = kBodyColor;  // the material of vertex colours without a material
};

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

  MaterialTable materials(*scene, file, ext, *io, options);
  bool vertex_colors = false;
  for (const MeshInstance& instance : instances) vertex_colors |= instance.mesh->HasVertexColors(0);
  const bool appearance = vertex_colors || materials.any_own();

  TriangleSoup soup;
  soup.positions.reserve(static_cast<std::size_t>(vertex_count));
  soup.triangles.reserve(static_cast<std::size_t>(triangle_count));
  MeshAppearance& look = soup.appearance;
  for (const MeshInstance& instance : instances) {
    const aiMesh& mesh = *instance.mesh;
    const std::uint32_t material =
        materials.material_of(mesh.mMaterialIndex, mesh.HasVertexColors(0));
    const aiVector3D* uvs = mesh.mTextureCoords[materials.uv_channel_of(mesh.mMaterialIndex)];
    const aiColor4D* colors = mesh.mColors[0];
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
      const std::array<unsigned, 3> corners =
          mirrored ? std::array<unsigned, 3>{a, c, b} : std::array<unsigned, 3>{a, b, c};
      soup.triangles.push_back({base + corners[0], base + corners[1], base + corners[2]});
      if (!appearance) continue;
      look.triangle_material.push_back(material);
      std::array<Vec3, 3> color;
      std::array<Eigen::Vector2d, 3> uv;
      for (std::size_t k = 0; k < 3; ++k) {
        color[k] = colors != nullptr ? to_linear(colors[corners[k]], materials.linear_colors())
                                     : Vec3::Ones();
        uv[k] = uvs != nullptr ? Eigen::Vector2d(static_cast<double>(uvs[corners[k]].x),
                                                 static_cast<double>(uvs[corners[k]].y))
                               : Eigen::Vector2d::Zero();
        if (!uv[k].allFinite()) uv[k].setZero();
      }
      look.corner_color.push_back(color);
      look.corner_uv.push_back(uv);
    }
  }
  if (appearance) materials.finish(look);
  if (soup.triangles.empty())
    throw_mesh_error(file, "the file holds no triangles (points or lines only bound no volume)");
  for (const Vec3& p : soup.positions)
    if (!p.allFinite())
      throw_mesh_error(file, "a vertex coordinate is not a finite number (after scale)");
  return soup;
}

}  // namespace mesh_detail
}  // namespace tumble
