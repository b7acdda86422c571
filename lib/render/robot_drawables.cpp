#include "render/robot_drawables.hpp"

#include <algorithm>

namespace rscene::render {
namespace {

using Eigen::Affine3d;
using Eigen::Vector3d;

Affine3d affine(const Pose& p) {
  Affine3d m = Affine3d::Identity();
  m.translate(p.position);
  m.rotate(p.orientation);
  return m;
}

Shape shapeOf(robot::GeometryKind k) {
  switch (k) {
    case robot::GeometryKind::Box: return Shape::Box;
    case robot::GeometryKind::Sphere: return Shape::Sphere;
    case robot::GeometryKind::Cylinder: return Shape::Cylinder;
    case robot::GeometryKind::Capsule: return Shape::Capsule;
    case robot::GeometryKind::Mesh: return Shape::Mesh;
  }
  return Shape::Box;
}

}  // namespace

int RobotDrawer::materialFor(const robot::Visual& v, const std::string& file) {
  bool mesh = v.geometry.kind == robot::GeometryKind::Mesh;
  // A mesh the file gives no colour or texture keeps its own materials:
  // the engine default (isDefault) is what tells the renderer so.
  if (!v.color && v.texture.empty() && mesh) return 0;
  // A texture without a colour is drawn as it is (white), a bare primitive grey.
  Eigen::Vector4f color = v.color              ? Eigen::Vector4f(v.color->cast<float>())
                          : !v.texture.empty() ? Eigen::Vector4f(1, 1, 1, 1)
                                               : kRobotGrey;
  auto key = std::make_tuple(color[0], color[1], color[2], color[3], v.texture);
  auto [it, fresh] = materials_.try_emplace(key, 0);
  if (!fresh) return it->second;
  RenderMaterial m;
  m.id = v.materialName.empty() ? "robot" : "robot:" + v.materialName;
  m.color = color;
  m.roughness = 0.6f;
  m.blend = color.w() < 0.999f;
  m.albedoTexture = v.texture;
  m.line = std::uint32_t(std::max(v.line, 0));
  m.file = file;
  m.isDefault = false;
  it->second = int(out_.materials.size());
  out_.materials.push_back(std::move(m));
  return it->second;
}

const Eigen::AlignedBox3d& RobotDrawer::meshBounds(const std::string& path) {
  auto [it, fresh] = meshBounds_.try_emplace(path);
  if (!fresh || path.empty() || !assets_.fileSystem().exists(path)) return it->second;
  std::string err;  // the renderer reports it (same cache, same reason)
  if (std::shared_ptr<const asset::Mesh> mesh = assets_.mesh(path, asset::MeshContent::Surface, &err))
    for (const asset::MeshPart& p : mesh->parts)
      for (std::size_t i = 0; i < p.vertexCount(); ++i)
        it->second.extend(Vector3d(p.positions[i * 3], p.positions[i * 3 + 1], p.positions[i * 3 + 2]));
  return it->second;
}

std::size_t RobotDrawer::add(const robot::Model& model, const std::vector<Pose>& poses, int robot, int segment) {
  std::size_t added = 0;
  for (std::size_t li = 0; li < model.links.size() && li < poses.size(); ++li) {
    const robot::Link& link = model.links[li];
    Affine3d linkWorld = affine(poses[li]);
    for (const robot::Visual& v : link.visuals) {
      const robot::Geometry& g = v.geometry;
      Drawable d;
      d.shape = shapeOf(g.kind);
      d.line = std::uint32_t(std::max(v.line, 0));
      d.file = link.file.empty() ? model.sourceFile : link.file;  // a module's link: the module
      d.material = materialFor(v, d.file);
      Affine3d pose = linkWorld * affine(v.origin);
      Eigen::AlignedBox3d local;
      switch (d.shape) {
        case Shape::Box: d.world = pose * Eigen::Scaling(g.size); break;
        case Shape::Sphere: d.world = pose * Eigen::Scaling(g.radius); break;
        case Shape::Cylinder: d.world = pose * Eigen::Scaling(g.radius, g.radius, g.length); break;
        case Shape::Capsule:  // RaiSim's length: between the centres of the two hemispheres
          d.capsuleRadius = g.radius;
          d.capsuleHeight = g.length;
          d.world = pose;
          break;
        case Shape::Mesh:
          d.meshPath = g.meshPath;
          d.world = pose * Eigen::Scaling(g.meshScale);
          d.placeholderWorld = pose * Eigen::Scaling(kRobotPlaceholderSide);
          local = meshBounds(g.meshPath);
          break;
        case Shape::Ground:
        case Shape::GrassBlade: break;
      }
      if (d.shape == Shape::Mesh)
        // A mesh that cannot be read is drawn as its placeholder box (a
        // zero mesh scale leaves nothing to invert: then a point).
        d.localBounds = !local.isEmpty()                             ? local
                        : std::abs(d.world.linear().determinant()) > 0 ? transformBox(d.world.inverse() * *d.placeholderWorld,
                                                                                      unitShapeBounds(Shape::Box))
                                                                       : Eigen::AlignedBox3d(Vector3d::Zero(), Vector3d::Zero());
      else
        d.localBounds = unitShapeBounds(d.shape, d.capsuleRadius, d.capsuleHeight);
      d.bounds = transformBox(d.world, d.localBounds);
      d.segment = segment;
      d.worldObject = true;
      if (robot >= 0) {
        d.attachment.kind = Mount::Kind::Articulated;
        d.attachment.index = robot;
        d.attachment.link = static_cast<int>(li);
        d.attachment.local = linkWorld.inverse() * d.world;
      }
      out_.bounds.extend(d.bounds);
      out_.drawables.push_back(std::move(d));
      ++added;
    }
  }
  return added;
}

}  // namespace rscene::render
