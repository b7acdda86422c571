#include "render/preparer.hpp"

namespace rscene::render::preparer_detail {

void Preparer::deformable(const Deformable& src, std::size_t index) {
  if (!src.visible || src.hiddenByGroup) return;
  Drawable d;
  d.shape = Shape::Mesh;
  d.meshPath = src.meshPath;
  d.line = lineOf(src.recordIndex);
  d.meshColumn = columnOf(src.recordIndex, "meshPath");
  d.material = materialIndex(src.material);
  d.segment = segment("deformable", src.recordIndex, src.path, src.id, "", -1);
  d.worldObject = true;  // a body of the world, as sensors see it
  d.world = affine(src.world) * Eigen::Scaling(src.scale);
  // A sheet of cloth is seen from both sides; a closed volume's back
  // faces are hidden anyway.
  d.doubleSided = src.kind == "cloth";
  if (objSurface(src, index, d)) return;
  addDrawable(std::move(d), meshBounds(src.meshPath));
}

bool Preparer::objSurface(const Deformable& src, std::size_t index, Drawable& d) {
  std::string ext = std::filesystem::path(src.meshPath).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  asset::ObjSurface obj;
  // Regular files only (a FIFO would block the read): anything else is
  // the assimp path's to report.
  const FileSystem& fs = assets().fileSystem();
  if (ext != ".obj" || fs.stat(src.meshPath).kind != FileKind::Regular ||
      !asset::loadObjSurface(fs, src.meshPath, obj, nullptr))
    return false;
  DeformedSurface surface = surfaceFromObj(obj, d.world);
  surface.mayFill = src.kind != "cloth" && src.kind != "mass_spring";
  // Its positions are world positions (trajectory frames replace them),
  // and a mirroring scale turns a closed surface's winding inside out.
  d.doubleSided = d.doubleSided || d.world.linear().determinant() < 0;
  d.world = Eigen::Affine3d::Identity();
  d.surface = int(out_.surfaces.size());
  surface.drawable = out_.drawables.size();
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3f& p : surface.positions) box.extend(p.cast<double>());
  out_.deformableSurfaces[index] = d.surface;
  out_.surfaces.push_back(std::move(surface));
  addDrawable(std::move(d), box);
  return true;
}

void Preparer::granular(const Granular& g, std::size_t index) {
  if (!g.visible || g.hiddenByGroup) return;
  std::uint64_t left = limits_.maxInstances - std::min(instancesDrawn_, limits_.maxInstances);
  std::vector<Vector3d> positions;
  std::vector<double> radii;
  std::string why = granularParticles(g, left, positions, radii);
  if (!why.empty()) {
    // A record whose grains cannot be made at all is the scene model's
    // finding (checkScene(): RS7082 at its key, as validate and sim say);
    // what is left is this renderer's own cap, --max-instances.
    std::vector<Vector3d> p;
    std::vector<double> r;
    if (!granularParticles(g, kMaxGranularParticles, p, r).empty()) {
      ok_ = false;
      return;
    }
    Diagnostic d;
    d.severity = Severity::Error;
    d.code = rs::RS9070;
    d.line = lineOf(g.recordIndex);
    d.column = d.line ? 1 : 0;
    d.message = why;
    d.hint = "maxParticles is " + std::to_string(g.maxParticles) + "; " + std::to_string(left) + " of --max-instances " +
             std::to_string(limits_.maxInstances) + " are left: fill a smaller box, space the particles wider, or raise "
             "--max-instances";
    diags_.push_back(std::move(d));
    ok_ = false;
    return;
  }
  if (positions.empty()) return;
  instancesDrawn_ += positions.size();
  Instanced b;
  b.kind = "granular";
  b.generated = positions.size();
  b.shape = Shape::Sphere;
  b.line = lineOf(g.recordIndex);
  b.segment = segment("granular", g.recordIndex, g.path, g.id, "", -1);
  b.worldObject = true;
  Affine3d frame = affine(g.world);
  const Vector4f sand(0.76f, 0.64f, 0.45f, 1.0f);
  b.worlds.reserve(positions.size());
  b.colors.assign(positions.size(), sand);
  b.instanceBounds.reserve(positions.size());
  b.radii.reserve(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    double r = std::isfinite(radii[i]) ? std::max(radii[i], 0.0) : 0.0;
    b.radii.push_back(r);
    Affine3d m = frame * Eigen::Translation3d(positions[i]) * Eigen::Scaling(r);
    b.worlds.push_back(m);
    b.instanceBounds.push_back(transformBox(m, unitShapeBounds(Shape::Sphere)));
    b.bounds.extend(b.instanceBounds.back());
  }
  out_.bounds.extend(b.bounds);
  out_.granularBatches[index] = int(out_.instanced.size());
  out_.instanced.push_back(std::move(b));
}

void Preparer::points(const PointCloud& src) {
  if (!src.enabled || src.hiddenByGroup || src.points.empty()) return;
  PointBatch pc;
  pc.segment = segment("point_cloud", src.recordIndex, src.path, src.id, "", -1);
  pc.pointSize = float(std::clamp(src.pointSize, 1.0, 64.0));
  std::size_t stride = std::size_t(std::max<std::int64_t>(src.renderedStride, 1));
  std::size_t count = drawnCount(src.points.size(), src.maxRendered, src.renderedStride);
  pc.points.reserve(count);
  pc.colors.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    std::size_t i = k * stride;
    pc.points.push_back(src.points[i].cast<float>());
    pc.colors.push_back(i < src.colors.size() ? toF(src.colors[i]) : Vector4f(1, 1, 1, 1));
    pc.bounds.extend(src.points[i]);
  }
  out_.bounds.extend(pc.bounds);
  out_.pointClouds.push_back(std::move(pc));
}

}  // namespace rscene::render::preparer_detail
