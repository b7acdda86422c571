#include "asset/mesh.hpp"

#include <assimp/config.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/IOStream.hpp>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <cstring>
#include <map>

namespace rscene::asset {
namespace {

// One file's bytes, served to assimp.
class BytesStream : public Assimp::IOStream {
 public:
  explicit BytesStream(std::string bytes) : bytes_(std::move(bytes)) {}
  size_t Read(void* buffer, size_t size, size_t count) override {
    if (size == 0) return 0;
    size_t n = std::min(count, (bytes_.size() - pos_) / size);
    std::memcpy(buffer, bytes_.data() + pos_, n * size);
    pos_ += n * size;
    return n;
  }
  size_t Write(const void*, size_t, size_t) override { return 0; }
  aiReturn Seek(size_t offset, aiOrigin origin) override {
    size_t base = origin == aiOrigin_SET ? 0 : origin == aiOrigin_CUR ? pos_ : bytes_.size();
    if (offset > bytes_.size() - base) return aiReturn_FAILURE;  // past the end (assimp never seeks back)
    pos_ = base + offset;
    return aiReturn_SUCCESS;
  }
  size_t Tell() const override { return pos_; }
  size_t FileSize() const override { return bytes_.size(); }
  void Flush() override {}

 private:
  std::string bytes_;
  size_t pos_ = 0;
};

// assimp's file access, routed through a FileSystem: the mesh file (read
// once beforehand) and the files it names.  Writing is refused.
class FileSystemIO : public Assimp::IOSystem {
 public:
  FileSystemIO(const FileSystem& fs, std::uint64_t maxBytes, std::string mainPath, std::string mainBytes)
      : fs_(fs), maxBytes_(maxBytes), mainPath_(std::move(mainPath)), mainBytes_(std::move(mainBytes)) {}
  bool Exists(const char* path) const override {
    return path == mainPath_ || fs_.stat(path).kind == FileKind::Regular;
  }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* path, const char* mode) override {
    if (std::strpbrk(mode, "wa+")) return nullptr;
    if (path == mainPath_) return new BytesStream(mainBytes_);
    std::string bytes;
    if (!fs_.read(path, bytes, nullptr, maxBytes_)) return nullptr;
    return new BytesStream(std::move(bytes));
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }

 private:
  const FileSystem& fs_;
  std::uint64_t maxBytes_;
  std::string mainPath_, mainBytes_;
};

std::string folderOf(const std::string& path) {
  std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

// A texture name as meshes write it (Windows separators, file:// URLs)
// made a path relative to the mesh's folder.
std::string texturePath(std::string name, const std::string& dir) {
  if (name.rfind("file://", 0) == 0) name.erase(0, 7);
  for (char& c : name)
    if (c == '\\') c = '/';
  if (!name.empty() && name.front() == '/') return name;
  while (name.rfind("./", 0) == 0) name.erase(0, 2);
  return dir == "/" ? "/" + name : dir + "/" + name;
}

class Reader {
 public:
  Reader(const FileSystem& fs, const std::string& path, const AssetLimits& limits, const TextureSource& textures,
         Mesh& out)
      : fs_(fs), dir_(folderOf(path)), limits_(limits), textures_(textures), out_(out) {}

  void geometry(const aiScene* scene) {
    MeshPart part;
    for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) appendTriangles(*scene->mMeshes[mi], part, false);
    if (!part.indices.empty()) out_.parts.push_back(std::move(part));
  }

  void surface(const aiScene* scene) {
    for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
      const aiMesh& mesh = *scene->mMeshes[mi];
      MeshPart part;
      appendTriangles(mesh, part, true);
      if (part.indices.empty()) continue;
      if (mesh.mMaterialIndex < scene->mNumMaterials) material(scene, *scene->mMaterials[mesh.mMaterialIndex], part);
      out_.parts.push_back(std::move(part));
    }
  }

 private:
  static void appendTriangles(const aiMesh& mesh, MeshPart& part, bool surface) {
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || mesh.mNumVertices == 0) return;
    auto base = static_cast<std::uint32_t>(part.vertexCount());
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines carry no surface
      for (int k = 0; k < 3; ++k) part.indices.push_back(base + face.mIndices[k]);
    }
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      part.positions.insert(part.positions.end(), {p.x, p.y, p.z});
      if (!surface) continue;
      aiVector3D n = mesh.mNormals ? mesh.mNormals[v] : aiVector3D(0, 0, 1);
      aiVector3D uv = mesh.mTextureCoords[0] ? mesh.mTextureCoords[0][v] : aiVector3D(0, 0, 0);
      part.normals.insert(part.normals.end(), {n.x, n.y, n.z});
      part.uvs.insert(part.uvs.end(), {uv.x, uv.y});
    }
  }

  void material(const aiScene* scene, const aiMaterial& mat, MeshPart& part) {
    MeshMaterial& m = part.material;
    aiColor4D c;
    if (aiGetMaterialColor(&mat, AI_MATKEY_BASE_COLOR, &c) == AI_SUCCESS ||
        aiGetMaterialColor(&mat, AI_MATKEY_COLOR_DIFFUSE, &c) == AI_SUCCESS)
      m.baseColor = {c.r, c.g, c.b, c.a};
    float f = 1;
    if (aiGetMaterialFloat(&mat, AI_MATKEY_OPACITY, &f) == AI_SUCCESS && f < 1) m.baseColor[3] *= f;
    if (aiGetMaterialFloat(&mat, AI_MATKEY_METALLIC_FACTOR, &f) == AI_SUCCESS) m.metallic = f;
    if (aiGetMaterialFloat(&mat, AI_MATKEY_ROUGHNESS_FACTOR, &f) == AI_SUCCESS) m.roughness = f;
    aiString name;
    if (mat.GetTexture(aiTextureType_BASE_COLOR, 0, &name) != AI_SUCCESS &&
        mat.GetTexture(aiTextureType_DIFFUSE, 0, &name) != AI_SUCCESS)
      return;
    m.texture = texture(scene, name.C_Str());
  }

  std::shared_ptr<const Image> texture(const aiScene* scene, const std::string& name) {
    std::string err;
    if (const aiTexture* embedded = scene->GetEmbeddedTexture(name.c_str())) {
      auto [it, fresh] = embedded_.try_emplace(embedded);
      if (!fresh) return it->second;
      auto image = std::make_shared<Image>();
      if (embedded->mHeight == 0) {  // compressed: mWidth bytes of a PNG or JPEG file
        std::string bytes(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth);
        if (!decodeImage(bytes, *image, &err, limits_.image)) {
          out_.warnings.push_back("embedded texture " + name + " is not drawn: " + err);
          return nullptr;
        }
      } else if (!uncompressed(*embedded, *image, err)) {
        out_.warnings.push_back("embedded texture " + name + " is not drawn: " + err);
        return nullptr;
      }
      return it->second = std::move(image);
    }
    std::string path = texturePath(name, dir_);
    std::shared_ptr<const Image> image;
    if (textures_) {
      image = textures_(path, &err);
    } else {
      std::string bytes;
      auto decoded = std::make_shared<Image>();
      if (fs_.read(path, bytes, &err, limits_.maxFileBytes) && decodeImage(bytes, *decoded, &err, limits_.image))
        image = std::move(decoded);
    }
    if (!image) out_.warnings.push_back("texture " + path + " is not drawn: " + err);
    return image;
  }

  bool uncompressed(const aiTexture& t, Image& image, std::string& err) const {
    std::uint64_t w = t.mWidth, h = t.mHeight;
    if (w * h > limits_.image.maxPixels) {
      err = "embedded image too large";
      return false;
    }
    image.width = int(w);
    image.height = int(h);
    image.rgba.resize(std::size_t(w * h * 4));
    for (std::size_t i = 0; i < w * h; ++i) {
      const aiTexel& texel = t.pcData[i];
      std::uint8_t* p = &image.rgba[i * 4];
      p[0] = texel.r, p[1] = texel.g, p[2] = texel.b, p[3] = texel.a;
    }
    return true;
  }

  const FileSystem& fs_;
  std::string dir_;
  const AssetLimits& limits_;
  const TextureSource& textures_;
  Mesh& out_;
  std::map<const aiTexture*, std::shared_ptr<const Image>> embedded_;
};

}  // namespace

std::size_t Mesh::triangleCount() const {
  std::size_t n = 0;
  for (const MeshPart& p : parts) n += p.indices.size() / 3;
  return n;
}

bool loadMesh(const FileSystem& fs, const std::string& path, MeshContent content, Mesh& out, std::string* error,
              const AssetLimits& limits, const TextureSource& textures) {
  out = Mesh{};
  std::string bytes, err;
  if (!fs.read(path, bytes, &err, limits.maxFileBytes)) {
    if (error) *error = err;
    return false;
  }
  Assimp::Importer importer;
  importer.SetIOHandler(new FileSystemIO(fs, limits.maxFileBytes, path, std::move(bytes)));  // importer owns it
  // assimp turns a COLLADA file's <up_axis>Z_UP</up_axis> into Y up by
  // rotating its root; this toolchain's world is z-up (RaiSim, ROS), so the
  // file's coordinates are taken as written, as RViz and MoveIt do (the
  // <unit> scale still applies).  Without it every robot .dae lies on its side.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
                   aiProcess_SortByPType;
  if (content == MeshContent::Surface) flags |= aiProcess_GenSmoothNormals | aiProcess_FlipUVs;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (!scene || !scene->mRootNode || (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)) {
    if (error) *error = scene ? "incomplete mesh file" : importer.GetErrorString();
    return false;
  }
  Reader reader(fs, path, limits, textures, out);
  if (content == MeshContent::Geometry) reader.geometry(scene);
  else reader.surface(scene);
  if (out.parts.empty()) {
    if (error) *error = "no triangles in mesh file";
    out = Mesh{};
    return false;
  }
  return true;
}

}  // namespace rscene::asset
