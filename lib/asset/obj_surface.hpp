// The vertices and faces of an OBJ file in the order the file lists them,
// which is what a deformable record's particles are: RaiSim builds a
// cloth's particles from the OBJ's `v` lines and its triangles from the
// `f` lines (polygons as fans, texture and normal indices ignored), and
// pinnedVertices are indices into those `v` lines.  assimp cannot serve
// here: it reorders and duplicates vertices per face.
//
// Read through a FileSystem with caps, so a hostile file is refused
// before it is allocated.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/filesystem.hpp"
#include "scene/triangle_surface.hpp"

namespace rscene::asset {

// Triangles are fans of the file's polygons.
using ObjSurface = TriangleSurface;

struct ObjLimits {
  std::uint64_t maxBytes = std::uint64_t{256} << 20;  // the file
  std::uint64_t maxVertices = 1'000'000;
  std::uint64_t maxTriangles = 2'000'000;
};

// False with `error` ("line 12: face index 40 is past the 36 vertices",
// "no triangles", "not an OBJ file: ...") when the file cannot be read or
// is not a usable OBJ surface.  Negative (relative) indices are resolved
// as OBJ says; a degenerate face (a repeated index) is kept out.
bool loadObjSurface(const FileSystem& fs, const std::string& path, ObjSurface& out, std::string* error,
                    const ObjLimits& limits = {});
// loadObjSurface over `fs` as the scene model's SurfaceReader
// (SceneCheckOptions::readSurface): validate --check-files, sim and render
// judge a deformable with its mesh through it.  `fs` must outlive it.
SurfaceReader objSurfaceReader(const FileSystem& fs);
// The same, from text already in memory (tests, fuzzing).
bool parseObjSurface(const std::string& text, ObjSurface& out, std::string* error, const ObjLimits& limits = {});

}  // namespace rscene::asset
