// The node a Mount names, for code that needs its record or its name (the
// simulator's lookups, what --allow-missing-assets detaches).
#pragma once
#include <string>

#include "scene/scene.hpp"

namespace rscene {

struct MountedNode {
  int recordIndex = -1;               // -1: the world, or an index out of range
  const std::string* id = nullptr;    // null with recordIndex -1
  const std::string* path = nullptr;
};

inline MountedNode mountedNode(const Scene& scene, const Mount& m) {
  auto of = [&](const auto& list) {
    if (m.index < 0 || static_cast<std::size_t>(m.index) >= list.size()) return MountedNode{};
    const auto& node = list[static_cast<std::size_t>(m.index)];
    return MountedNode{node.recordIndex, &node.id, &node.path};
  };
  switch (m.kind) {
    case Mount::Kind::Object: return of(scene.objects);
    case Mount::Kind::Compound: return of(scene.compounds);
    case Mount::Kind::Articulated: return of(scene.articulated);
    case Mount::Kind::World: break;
  }
  return {};
}

}  // namespace rscene
