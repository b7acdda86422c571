#include "render/mesh.hpp"

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cmath>
#include <cstring>

#include "core/io.hpp"

namespace rscene::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

void vertex(MeshData& m, double x, double y, double z, double nx, double ny, double nz, double u, double v) {
  m.vertices.insert(m.vertices.end(), {float(x), float(y), float(z), float(nx), float(ny), float(nz), float(u),
                                       float(v)});
}

void quad(MeshData& m, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
  m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
}

// A surface of revolution around z: rings of (radius, z, normal r, normal z).
struct Ring {
  double r, z, nr, nz, v;
};

void revolve(MeshData& m, const std::vector<Ring>& rings, int slices) {
  auto base = std::uint32_t(m.vertexCount());
  for (const Ring& ring : rings)
    for (int s = 0; s <= slices; ++s) {
      double a = 2 * kPi * s / slices, c = std::cos(a), sn = std::sin(a);
      vertex(m, ring.r * c, ring.r * sn, ring.z, ring.nr * c, ring.nr * sn, ring.nz, double(s) / slices, ring.v);
    }
  auto row = std::uint32_t(slices + 1);
  for (std::uint32_t k = 0; k + 1 < rings.size(); ++k)
    for (std::uint32_t s = 0; s < std::uint32_t(slices); ++s)
      quad(m, base + k * row + s, base + k * row + s + 1, base + (k + 1) * row + s + 1, base + (k + 1) * row + s);
}

void disk(MeshData& m, double z, double nz, int slices) {
  auto center = std::uint32_t(m.vertexCount());
  vertex(m, 0, 0, z, 0, 0, nz, 0.5, 0.5);
  for (int s = 0; s <= slices; ++s) {
    double a = 2 * kPi * s / slices;
    vertex(m, std::cos(a), std::sin(a), z, 0, 0, nz, 0.5 + 0.5 * std::cos(a), 0.5 + 0.5 * std::sin(a));
  }
  for (std::uint32_t s = 0; s < std::uint32_t(slices); ++s) {
    if (nz > 0) m.indices.insert(m.indices.end(), {center, center + 1 + s, center + 2 + s});
    else m.indices.insert(m.indices.end(), {center, center + 2 + s, center + 1 + s});
  }
}

}  // namespace

MeshData unitBox() {
  MeshData m;
  static const float n[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const auto& f : n) {
    Eigen::Vector3d normal(f[0], f[1], f[2]);
    Eigen::Vector3d u = std::abs(normal.z()) > 0.5 ? Eigen::Vector3d(1, 0, 0) : Eigen::Vector3d(0, 0, 1);
    Eigen::Vector3d t = u.cross(normal), b = normal.cross(t);
    auto base = std::uint32_t(m.vertexCount());
    const double corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
      Eigen::Vector3d p = 0.5 * (normal + c[0] * t + c[1] * b);
      vertex(m, p.x(), p.y(), p.z(), normal.x(), normal.y(), normal.z(), (c[0] + 1) / 2, (c[1] + 1) / 2);
    }
    quad(m, base, base + 1, base + 2, base + 3);
  }
  return m;
}

MeshData unitSphere(int slices, int stacks) {
  std::vector<Ring> rings;
  for (int k = 0; k <= stacks; ++k) {
    double phi = kPi * k / stacks - kPi / 2;
    rings.push_back({std::cos(phi), std::sin(phi), std::cos(phi), std::sin(phi), double(k) / stacks});
  }
  MeshData m;
  revolve(m, rings, slices);
  return m;
}

MeshData unitCylinder(int slices) {
  MeshData m;
  revolve(m, {{1, -0.5, 1, 0, 0}, {1, 0.5, 1, 0, 1}}, slices);
  disk(m, 0.5, 1, slices);
  disk(m, -0.5, -1, slices);
  return m;
}

MeshData capsule(double radius, double height, int slices) {
  std::vector<Ring> rings;
  int half = slices / 4;
  for (int k = 0; k <= half; ++k) {
    double phi = -kPi / 2 + (kPi / 2) * k / half;
    rings.push_back({radius * std::cos(phi), -height / 2 + radius * std::sin(phi), std::cos(phi), std::sin(phi), 0});
  }
  for (int k = 0; k <= half; ++k) {
    double phi = (kPi / 2) * k / half;
    rings.push_back({radius * std::cos(phi), height / 2 + radius * std::sin(phi), std::cos(phi), std::sin(phi), 1});
  }
  MeshData m;
  revolve(m, rings, slices);
  return m;
}

MeshData unitPlane() {
  MeshData m;
  vertex(m, -0.5, -0.5, 0, 0, 0, 1, 0, 0);
  vertex(m, 0.5, -0.5, 0, 0, 0, 1, 1, 0);
  vertex(m, 0.5, 0.5, 0, 0, 0, 1, 1, 1);
  vertex(m, -0.5, 0.5, 0, 0, 0, 1, 0, 1);
  quad(m, 0, 1, 2, 3);
  return m;
}

namespace {

std::string folderOf(const std::string& path) {
  std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

void readTexture(const aiScene* scene, const aiMaterial* mat, const std::string& dir, MeshPart& part,
                 LoadedMesh& out) {
  aiString texPath;
  if (mat->GetTexture(aiTextureType_BASE_COLOR, 0, &texPath) != AI_SUCCESS &&
      mat->GetTexture(aiTextureType_DIFFUSE, 0, &texPath) != AI_SUCCESS)
    return;
  std::string name = texPath.C_Str();
  std::string err;
  if (const aiTexture* embedded = scene->GetEmbeddedTexture(texPath.C_Str())) {
    if (embedded->mHeight == 0) {
      std::string bytes(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth);
      if (!decodePng(bytes, part.texture, &err))
        out.warnings.push_back("embedded texture " + name + " is not drawn: " + err);
    } else {
      part.texture.width = int(embedded->mWidth);
      part.texture.height = int(embedded->mHeight);
      part.texture.rgba.resize(std::size_t(embedded->mWidth) * embedded->mHeight * 4);
      for (std::size_t i = 0; i < std::size_t(embedded->mWidth) * embedded->mHeight; ++i) {
        const aiTexel& t = embedded->pcData[i];
        std::uint8_t* p = &part.texture.rgba[i * 4];
        p[0] = t.r, p[1] = t.g, p[2] = t.b, p[3] = t.a;
      }
    }
    return;
  }
  std::string full = !name.empty() && name.front() == '/' ? name : dir + "/" + name;
  std::string bytes;
  if (!readFile(full, bytes, &err)) {
    out.warnings.push_back("texture " + full + " is not drawn: " + err);
    return;
  }
  if (!decodePng(bytes, part.texture, &err)) {
    part.texture = Image{};
    out.warnings.push_back("texture " + full + " is not drawn: " + err);
  }
}

}  // namespace

bool loadMesh(const std::string& path, LoadedMesh& out, std::string* error) {
  out = LoadedMesh{};
  const unsigned flags = aiProcess_Triangulate | aiProcess_GenSmoothNormals | aiProcess_PreTransformVertices |
                         aiProcess_JoinIdenticalVertices | aiProcess_FlipUVs | aiProcess_SortByPType;
  const aiScene* scene = aiImportFile(path.c_str(), flags);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    if (error) *error = aiGetErrorString();
    if (scene) aiReleaseImport(scene);
    return false;
  }
  std::string dir = folderOf(path);
  for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
    const aiMesh* mesh = scene->mMeshes[mi];
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || mesh->mNumVertices == 0) continue;
    MeshPart part;
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      aiVector3D n = mesh->mNormals ? mesh->mNormals[v] : aiVector3D(0, 0, 1);
      aiVector3D uv = mesh->mTextureCoords[0] ? mesh->mTextureCoords[0][v] : aiVector3D(0, 0, 0);
      part.mesh.vertices.insert(part.mesh.vertices.end(), {p.x, p.y, p.z, n.x, n.y, n.z, uv.x, uv.y});
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f)
      if (mesh->mFaces[f].mNumIndices == 3)
        part.mesh.indices.insert(part.mesh.indices.end(),
                                 {mesh->mFaces[f].mIndices[0], mesh->mFaces[f].mIndices[1], mesh->mFaces[f].mIndices[2]});
    if (mesh->mMaterialIndex < scene->mNumMaterials) {
      const aiMaterial* mat = scene->mMaterials[mesh->mMaterialIndex];
      aiColor4D c;
      if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &c) == AI_SUCCESS ||
          aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == AI_SUCCESS)
        part.baseColor = Eigen::Vector4f(c.r, c.g, c.b, c.a);
      float opacity = 1;
      if (aiGetMaterialFloat(mat, AI_MATKEY_OPACITY, &opacity) == AI_SUCCESS && opacity < 1)
        part.baseColor.w() *= opacity;
      float f = 0;
      if (aiGetMaterialFloat(mat, AI_MATKEY_METALLIC_FACTOR, &f) == AI_SUCCESS) part.metallic = f;
      if (aiGetMaterialFloat(mat, AI_MATKEY_ROUGHNESS_FACTOR, &f) == AI_SUCCESS) part.roughness = f;
      readTexture(scene, mat, dir, part, out);
    }
    out.parts.push_back(std::move(part));
  }
  aiReleaseImport(scene);
  if (out.parts.empty()) {
    if (error) *error = "no triangles in mesh file";
    return false;
  }
  return true;
}

}  // namespace rscene::render
