// SPDX-License-Identifier: BSD-3-Clause
#include "geometry/mesh_loader.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/ObjMaterial.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

#include "base/limits.h"
#include "geometry/detail/mesh_file_checks.h"
#include "geometry/detail/ply_strips.h"

namespace voxlink::geometry {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// The files assimp opens for one load. Falls back to OBJ-stem.mtl when the OBJ names an MTL file
// that does not exist, and checks each material library before assimp reads it: on a refused one
// it records the error and throws, which Importer::ReadFile turns into "no scene".
class MeshFileIo : public Assimp::DefaultIOSystem {
 public:
  MeshFileIo(std::string mainPath, bool mainIsObj, std::string fallback)
      : mainPath_(std::move(mainPath)), mainIsObj_(mainIsObj), fallback_(std::move(fallback)) {}
  bool Exists(const char* file) const override {
    return DefaultIOSystem::Exists(file) || (isMissingMtl(file) && !fallback_.empty());
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    const std::string path = isMissingMtl(file) && !fallback_.empty() ? fallback_ : file;
    if (isMaterialLibrary(path)) {
      Status checked = checkMtlFile(path, mainPath_);
      if (!checked) {
        refused_ = checked;
        throw std::runtime_error(checked.message());
      }
    }
    return DefaultIOSystem::Open(path.c_str(), mode);
  }
  const Status& refused() const { return refused_; }

 private:
  bool isMissingMtl(const char* file) const {
    return lower(fs::path(file).extension().string()) == ".mtl" && !DefaultIOSystem::Exists(file);
  }
  // An OBJ's `mtllib` may name any file: every file but the OBJ itself is one then. The file
  // loadMesh was given is never one, whatever its name.
  bool isMaterialLibrary(const std::string& path) const {
    std::error_code ec;
    if (fs::equivalent(path, mainPath_, ec)) return false;
    return mainIsObj_ || lower(fs::path(path).extension().string()) == ".mtl";
  }
  std::string mainPath_;
  bool mainIsObj_;
  std::string fallback_;
  Status refused_;
};

// assimp's messages may span lines and quote whole lines of a damaged file (kilobytes).
std::string oneLine(std::string s) {
  constexpr size_t kMaxChars = 240;
  std::replace(s.begin(), s.end(), '\n', ' ');
  std::replace(s.begin(), s.end(), '\r', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  if (s.size() > kMaxChars) s = s.substr(0, kMaxChars) + "...";
  return s;
}

// The line of the first `v` record with a non-finite coordinate, or 0. Only run once a
// non-finite position was seen: assimp does not report lines.
size_t findNonFiniteObjVertexLine(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    if (line.size() < 2 || line[0] != 'v' || (line[1] != ' ' && line[1] != '\t')) continue;
    const char* p = line.c_str() + 1;
    for (int c = 0; c < 3; ++c) {
      char* end = nullptr;
      const double value = std::strtod(p, &end);
      if (end == p) break;
      if (!std::isfinite(value)) return number;
      p = end;
    }
  }
  return 0;
}

float mean(const aiColor3D& c) { return (c.r + c.g + c.b) / 3.0f; }

Material convertMaterial(const aiMaterial& in) {
  Material m;
  aiString name;
  if (in.Get(AI_MATKEY_NAME, name) == AI_SUCCESS) m.name = name.C_Str();
  if (m.name.empty()) m.name = "default";
  aiColor3D color;
  if (in.Get(AI_MATKEY_COLOR_DIFFUSE, color) == AI_SUCCESS) m.color = {color.r, color.g, color.b};
  if (in.Get(AI_MATKEY_COLOR_EMISSIVE, color) == AI_SUCCESS)
    m.emission = {color.r, color.g, color.b};
  float opacity = 1.0f;
  if (in.Get(AI_MATKEY_OPACITY, opacity) == AI_SUCCESS) m.opacity = std::clamp(opacity, 0.0f, 1.0f);
  aiColor3D specular(0, 0, 0);
  in.Get(AI_MATKEY_COLOR_SPECULAR, specular);
  const float ks = std::clamp(mean(specular), 0.0f, 1.0f);
  int illum = -1;
  in.Get(AI_MATKEY_OBJ_ILLUM, illum);
  if (illum == 3 || illum == 5) {
    m.reflectivity = ks > 0.0f ? ks : 1.0f;
  } else if (illum == 4 || illum == 6 || illum == 7) {
    m.reflectivity = ks;
    m.transmission = m.opacity < 1.0f ? 1.0f - m.opacity : 1.0f;
  }
  float ior = 1.0f;
  if (m.transmission > 0.0f && in.Get(AI_MATKEY_REFRACTI, ior) == AI_SUCCESS && ior > 0.0f)
    m.refractiveIndex = ior;
  return m;
}

struct Matrix3x4 {
  float m[3][4];
};

Matrix3x4 toMatrix(const aiMatrix4x4& t) {
  return {{{t.a1, t.a2, t.a3, t.a4}, {t.b1, t.b2, t.b3, t.b4}, {t.c1, t.c2, t.c3, t.c4}}};
}

bool isIdentity(const aiMatrix4x4& t) { return t.IsIdentity(); }

struct Collector {
  const aiScene& scene;
  TriangleMesh& out;
  bool allHaveNormals = true;

  void visit(const aiNode& node, const aiMatrix4x4& parent) {
    const aiMatrix4x4 transform = parent * node.mTransformation;
    for (unsigned i = 0; i < node.mNumMeshes; ++i)
      append(*scene.mMeshes[node.mMeshes[i]], transform);
    for (unsigned i = 0; i < node.mNumChildren; ++i) visit(*node.mChildren[i], transform);
  }

  void append(const aiMesh& mesh, const aiMatrix4x4& transform) {
    size_t triangles = 0;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) triangles += mesh.mFaces[f].mNumIndices == 3;
    if (triangles == 0) return;
    const uint32_t base = static_cast<uint32_t>(out.vertexCount());
    const bool identity = isIdentity(transform);
    const Matrix3x4 t = toMatrix(transform);
    aiMatrix3x3 normalTransform(transform);
    normalTransform.Inverse().Transpose();
    if (!mesh.HasNormals()) allHaveNormals = false;
    out.positions.reserve(out.positions.size() + 3 * size_t(mesh.mNumVertices));
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      if (identity) {
        out.positions.insert(out.positions.end(), {p.x, p.y, p.z});
      } else {
        for (int r = 0; r < 3; ++r)
          out.positions.push_back(t.m[r][0] * p.x + t.m[r][1] * p.y + t.m[r][2] * p.z + t.m[r][3]);
      }
      if (allHaveNormals) {
        aiVector3D n = identity ? mesh.mNormals[v] : normalTransform * mesh.mNormals[v];
        const float length = n.Length();
        if (length > 0.0f) n /= length;
        out.normals.insert(out.normals.end(), {n.x, n.y, n.z});
      }
    }
    out.triangles.reserve(out.triangles.size() + 3 * triangles);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      out.triangles.insert(out.triangles.end(), {base + face.mIndices[0], base + face.mIndices[1],
                                                 base + face.mIndices[2]});
    }
    out.triangleMaterials.insert(out.triangleMaterials.end(), triangles,
                                 static_cast<uint16_t>(mesh.mMaterialIndex));
  }
};

}  // namespace

// Debian's assimp 5.2 is built with its internal assertions on (ASSIMP_BUILD_DEBUG), and a
// violated one aborts the process: a damaged PLY whose faces disagree with their count ended
// `voxlink scene build` in TriangulateProcess. Those assertions call Assimp::aiAssertViolation
// through the dynamic linker, so the definition below replaces assimp's: it records what failed
// and throws; Importer::ReadFile catches any exception and returns no scene ("Unknown
// exception"), and loadMesh reports the recorded check instead.
thread_local std::string assimpAssertion;

}  // namespace voxlink::geometry

namespace Assimp {
void aiAssertViolation(const char* failedExpression, const char* file, int line);
void aiAssertViolation(const char* failedExpression, const char* file, int line) {
  voxlink::geometry::assimpAssertion =
      voxlink::cat("assimp's internal check failed: ", failedExpression, " (",
                   std::filesystem::path(file).filename().string(), ":", line, ")");
  throw std::runtime_error(voxlink::geometry::assimpAssertion);
}
}  // namespace Assimp

namespace voxlink::geometry {

Result<TriangleMesh> loadMesh(const std::string& path, const MeshLoadOptions& options) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    return makeError(ErrorCode::kIo, path,
                     fs::exists(path, ec) ? ": not a regular file (a directory, FIFO or device)"
                                          : ": no such file");
  const std::string extension = lower(fs::path(path).extension().string());
  const bool isObj = extension == ".obj";

  Assimp::Importer importer;
  std::string fallbackMtl;
  if (isObj) {
    fs::path mtl = fs::path(path);
    mtl.replace_extension(".mtl");
    if (fs::is_regular_file(mtl, ec)) fallbackMtl = mtl.string();
  }
  auto* io = new MeshFileIo(path, isObj, fallbackMtl);
  importer.SetIOHandler(io);  // the importer owns it
  // Keep degenerate triangles and lines out of the triangulation's way: no FindDegenerates.
  uint64_t declaredFaces = 0;  // what the header says, to catch a load that lost faces
  if (extension == ".ply" || looksLikePly(path)) {
    VOXLINK_ASSIGN_OR_RETURN(const PlyHeader header, readPlyHeader(path));
    VOXLINK_RETURN_IF_ERROR(checkPlyFile(path, header));
    if (header.find("tristrips")) return loadPlyWithStrips(path, header, options.maxTriangles);
    if (const PlyElement* faces = header.find("face")) declaredFaces = faces->count;
  } else {
    declaredFaces = declaredOffFaceCount(path);
  }
  if (extension == ".off" || looksLikeOff(path)) VOXLINK_RETURN_IF_ERROR(checkOffFile(path));
  assimpAssertion.clear();
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_ValidateDataStructure | aiProcess_Triangulate);
  if (!io->refused()) return io->refused().error();
  if (scene == nullptr || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) ||
      scene->mRootNode == nullptr) {
    return makeError(
        ErrorCode::kCorrupt, path, ": cannot parse: ",
        oneLine(assimpAssertion.empty() ? importer.GetErrorString() : assimpAssertion));
  }
  if (scene->mNumMaterials > 65536) {
    return makeError(ErrorCode::kTooLarge, path, ": ", scene->mNumMaterials,
                     " materials, more than 65536");
  }
  uint64_t faces = 0;
  for (unsigned i = 0; i < scene->mNumMeshes; ++i) faces += scene->mMeshes[i]->mNumFaces;
  if (faces > options.maxTriangles) {
    return makeError(ErrorCode::kTooLarge, path, ": ", faces, " faces, more than the limit of ",
                     options.maxTriangles, " triangles");
  }

  TriangleMesh mesh;
  Collector collector{*scene, mesh};
  collector.visit(*scene->mRootNode, aiMatrix4x4());
  if (!collector.allHaveNormals) mesh.normals.clear();
  if (mesh.triangleCount() == 0) return makeError(ErrorCode::kCorrupt, path, ": no triangles");
  // A polygon gives at least one triangle: far fewer than the header's faces means faces were
  // lost (points and lines, or a layout assimp misreads), not a smaller mesh.
  if (mesh.triangleCount() < declaredFaces / 2)
    return makeError(ErrorCode::kCorrupt, path, ": the header declares ", declaredFaces,
                     " faces but only ", mesh.triangleCount(),
                     " triangles loaded; refusing a mesh that lost faces");
  if (mesh.triangleCount() > options.maxTriangles) {
    return makeError(ErrorCode::kTooLarge, path, ": ", mesh.triangleCount(),
                     " triangles, more than the limit of ", options.maxTriangles);
  }
  if (mesh.vertexCount() > std::numeric_limits<uint32_t>::max()) {
    return makeError(ErrorCode::kTooLarge, path, ": ", mesh.vertexCount(),
                     " vertices, more than 2^32-1");
  }
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    if (std::isfinite(mesh.positions[i])) continue;
    const size_t line = isObj ? findNonFiniteObjVertexLine(path) : 0;
    if (line > 0) {
      return makeError(ErrorCode::kNonFinite, path, ": line ", line,
                       ": non-finite vertex coordinate");
    }
    return makeError(ErrorCode::kNonFinite, path, ": vertex ", i / 3, ": non-finite coordinate ",
                     mesh.positions[i]);
  }
  mesh.materials.reserve(scene->mNumMaterials);
  for (unsigned i = 0; i < scene->mNumMaterials; ++i)
    mesh.materials.push_back(convertMaterial(*scene->mMaterials[i]));
  if (mesh.materials.empty()) mesh.materials.push_back(Material{"default"});
  return mesh;
}

}  // namespace voxlink::geometry
