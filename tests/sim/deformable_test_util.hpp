// Builders shared by the deformable solver's tests: hand-made models, grid
// cloth meshes as OBJ text, and a record with the schema's defaults.
#pragma once
#include <cstdio>
#include <string>

#include "asset/obj_surface.hpp"
#include "scene/deformable_model.hpp"
#include "sim/deformable_solver.hpp"
#include "sim/surface_query.hpp"

namespace rscene::sim::test {

// A deformable record with lib/core/schema_table.cpp's defaults.
inline Deformable defaultRecord(const std::string& kind = "cloth") {
  Deformable d;
  d.kind = kind;
  d.meshPath = "mesh.obj";
  d.totalMass = 1;
  d.distanceCompliance = 0;
  d.distanceStiffness = 1000;
  d.bendCompliance = 0;
  d.bendStiffness = 100;
  d.youngsModulus = 0;
  d.poissonRatio = 0.3;
  d.thickness = 0.002;
  d.damping = 0.01;
  d.collisionRadius = 0.01;
  d.iterations = 20;
  d.substeps = 1;
  d.solverMode = "xpbd";
  d.particleMode = "skinned";
  d.particleSpacing = 0.05;
  d.visible = d.collidable = true;
  d.collisionGroup = 1;
  d.collisionMask = ~std::uint64_t{0};
  return d;
}

// An n x n vertex grid of side `size` in the plane z = 0, centred on the
// origin, vertex (i, j) at index j * n + i; two triangles a cell, their
// diagonals alternating from cell to cell (one diagonal everywhere would
// let the cloth fold along it only).
inline std::string gridObj(int n, double size) {
  std::string s;
  char buf[96];
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      std::snprintf(buf, sizeof buf, "v %.17g %.17g 0\n", -size / 2 + size * i / (n - 1), -size / 2 + size * j / (n - 1));
      s += buf;
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      int a = j * n + i + 1, b = a + 1, c = a + n, d = c + 1;  // OBJ is one-based
      if ((i + j) % 2)
        std::snprintf(buf, sizeof buf, "f %d %d %d\nf %d %d %d\n", a, b, d, a, d, c);
      else
        std::snprintf(buf, sizeof buf, "f %d %d %d\nf %d %d %d\n", a, b, c, b, d, c);
      s += buf;
    }
  return s;
}

// A closed axis-aligned cube of side `size` centred on the origin.
inline std::string cubeObj(double size) {
  char buf[512];
  double h = size / 2;
  std::snprintf(buf, sizeof buf,
                "v %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\nv %g %g %g\n", -h,
                -h, -h, h, -h, -h, h, h, -h, -h, h, -h, -h, -h, h, h, -h, h, h, h, h, -h, h, h);
  return std::string(buf) +
         "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";
}

inline asset::ObjSurface surfaceOf(const std::string& obj) {
  asset::ObjSurface s;
  std::string error;
  if (!asset::parseObjSurface(obj, s, &error)) std::fprintf(stderr, "bad test mesh: %s\n", error.c_str());
  return s;
}

// Builds the model of `record` on `obj`; empty error on success.
inline std::unique_ptr<XpbdDeformable> build(const Deformable& record, const std::string& obj, std::string* error = nullptr,
                                             std::string* field = nullptr) {
  DeformableModel m;
  std::string e, f;
  bool ok = buildDeformableModel(record, surfaceOf(obj), m, e, f);
  if (error) *error = e;
  if (field) *field = f;
  return ok ? std::make_unique<XpbdDeformable>(std::move(m)) : nullptr;
}

inline void run(DeformableBody& body, SurfaceQuery& s, double seconds, double dt = 0.005,
                const Eigen::Vector3d& g = Eigen::Vector3d(0, 0, -9.81)) {
  for (long i = 0, n = std::lround(seconds / dt); i < n; ++i) body.step(dt, g, s);
}

inline Eigen::Vector3d centroid(const std::vector<Eigen::Vector3d>& p) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& x : p) c += x;
  return c / static_cast<double>(p.size());
}

inline double lowest(const std::vector<Eigen::Vector3d>& p) {
  double z = INFINITY;
  for (const auto& x : p) z = std::min(z, x.z());
  return z;
}

}  // namespace rscene::sim::test
