// Closest points between a particle's centre and one Bullet collision
// shape, in the shape's own frame: the geometry BulletSurfaces
// (bullet_surfaces.hpp) asks for every particle and every surface near it.
//
// Solids (planes, boxes, spheres, cylinders, capsules, convex hulls, height
// fields) have an inside: a centre inside is at a negative distance and is
// pushed out through the nearest face.  Triangle meshes are two-sided
// surfaces, as Bullet collides them: a centre is pushed back to the side it
// is on.  Primitives are closed-form (a plane costs one dot product);
// convex hulls by their face planes, and near their edges and corners (or
// any other convex shape) through Bullet's GJK/EPA with a sphere probe;
// meshes and height fields visit only the triangles under the probe's box.
#pragma once
#include <LinearMath/btVector3.h>

#include <vector>

class btConcaveShape;
class btConvexHullShape;
class btConvexShape;

namespace rscene::sim {

// The surface point closest to the centre, the unit normal there (from the
// surface toward the centre; out of the solid when the centre is inside)
// and the signed distance of the centre from the surface (< 0 inside).
struct LocalContact {
  btVector3 point{0, 0, 0};
  btVector3 normal{0, 0, 1};
  double distance = 0;
};

// Half-space below the plane n . x = k (n unit).
LocalContact planeContact(const btVector3& n, double k, const btVector3& c);
LocalContact boxContact(const btVector3& half, const btVector3& c);
LocalContact sphereContact(double radius, const btVector3& c);
// Solid cylinder and capsule along local axis `axis` (0, 1, 2): radius,
// half of the length of the cylinder / of the capsule's inner segment.
LocalContact cylinderContact(int axis, double radius, double halfLength, const btVector3& c);
LocalContact capsuleContact(int axis, double radius, double halfLength, const btVector3& c);
// Any convex shape (with its collision margin) by GJK/EPA against a sphere
// of radius `probe` (> 0) at c; false when GJK gives no answer.
bool convexContact(const btConvexShape& shape, const btVector3& c, double probe, LocalContact& out);

// A convex hull's face planes (outward unit normals, n . x = offset on the
// face), computed once per shape: most queries near a hull are answered
// from them in closed form, GJK only where they cannot be.
struct HullPlanes {
  std::vector<btVector3> normals;
  std::vector<double> offsets;
};
HullPlanes hullPlanes(const btConvexHullShape& shape);
// The contact with the hull grown by its collision margin, when the
// centre is inside it or over the inside of one face; false (out
// untouched) near an edge or a corner, where convexContact answers.
bool hullFaceContact(const HullPlanes& hull, double margin, const btVector3& c, LocalContact& out);

// Contacts of the centre with a concave shape (triangle mesh, scaled
// mesh, height field) within `reach` of it: one per local minimum of the
// distance over the surface (a flat mesh gives one contact however many
// triangles lie under the probe; a groove gives one per side).  A height
// field is a solid below its surface: a centre under it gets one contact
// pushing it up through the triangle above it.  `scratch` is reused
// between calls to spare allocations.
struct TriangleHit {
  btVector3 a, b, c;  // the triangle
  LocalContact contact;
  bool onFace = false;  // the closest point is inside the triangle (not on an edge or corner)
};
void concaveContacts(const btConcaveShape& shape, bool heightField, const btVector3& c, double reach,
                     std::vector<TriangleHit>& scratch, std::vector<LocalContact>& out);

}  // namespace rscene::sim
