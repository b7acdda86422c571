// Readers of visual_records.hpp's records from one record, and the pose
// reader every node record shares (internal to lib/scene: scene.cpp's
// Builder calls them and resolves parents and world poses).
#pragma once
#include <functional>
#include <string>
#include <string_view>

#include "core/document.hpp"
#include "scene/reader.hpp"
#include "scene/visual_records.hpp"

namespace rscene {

// A pose as written: the vec3 field `pos` and the quaternion (w, x, y, z) `rot`.
Pose readPose(const RecordReader& r, std::string_view pos, std::string_view rot);

using AssetPath = std::function<std::string(const std::string&)>;  // resolves an asset path as written

Decal readDecal(const Document& doc, const RecordReader& r, int idx, const AssetPath& asset);
LocalFog readLocalFog(const Document& doc, const RecordReader& r, int idx);
IrradianceVolume readIrradianceVolume(const Document& doc, const RecordReader& r, int idx);
ReflectionProbe readReflectionProbe(const Document& doc, const RecordReader& r, int idx);
FoliageLayer readFoliageLayer(const RecordReader& r, int idx, const AssetPath& asset);
Deformable readDeformable(const Document& doc, const RecordReader& r, int idx, const AssetPath& asset);
Granular readGranular(const Document& doc, const RecordReader& r, int idx);

}  // namespace rscene
