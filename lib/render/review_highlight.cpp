#include "render/review_highlight.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "render/camera.hpp"

namespace rscene::render::review {
namespace {

std::uint32_t segmentLine(const RenderScene& s, int segment) {
  return segment >= 0 && std::size_t(segment) < s.segments.size() ? s.segments[std::size_t(segment)].line : 0;
}

std::uint32_t materialLine(const RenderScene& s, int material) {
  if (material < 0 || std::size_t(material) >= s.materials.size()) return 0;
  const RenderMaterial& m = s.materials[std::size_t(material)];
  return m.isDefault || !m.file.empty() ? 0 : m.line;
}

bool near(const Eigen::Matrix4d& a, const Eigen::Matrix4d& b) { return (a - b).cwiseAbs().maxCoeff() <= 1e-9; }
bool near(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
  if (a.isEmpty() || b.isEmpty()) return a.isEmpty() == b.isEmpty();
  return (a.min() - b.min()).cwiseAbs().maxCoeff() <= 1e-9 && (a.max() - b.max()).cwiseAbs().maxCoeff() <= 1e-9;
}

// Whether a part stands elsewhere or has another shape (an outline of its
// old place says something), and whether anything of its look changed.
struct PartChange {
  bool moved = false, look = false;
};

PartChange compare(const RenderScene& a, const Item& ia, const RenderScene& b, const Item& ib) {
  PartChange c;
  if (ia.kind != ib.kind) return {true, true};
  c.moved = !near(ia.bounds, ib.bounds);
  auto colorOf = [](const RenderScene& s, int m) {
    return m >= 0 && std::size_t(m) < s.materials.size() ? s.materials[std::size_t(m)].color : Eigen::Vector4f::Zero();
  };
  switch (ia.kind) {
    case ItemKind::Drawable: {
      const Drawable& da = a.drawables[ia.index];
      const Drawable& db = b.drawables[ib.index];
      c.moved = c.moved || !near(da.world.matrix(), db.world.matrix()) || da.shape != db.shape ||
                da.meshPath != db.meshPath || da.capsuleRadius != db.capsuleRadius ||
                da.capsuleHeight != db.capsuleHeight;
      const RenderMaterial* ma = da.material >= 0 && std::size_t(da.material) < a.materials.size() ? &a.materials[std::size_t(da.material)] : nullptr;
      const RenderMaterial* mb = db.material >= 0 && std::size_t(db.material) < b.materials.size() ? &b.materials[std::size_t(db.material)] : nullptr;
      c.look = (ma == nullptr) != (mb == nullptr) ||
               (ma && (ma->color != mb->color || ma->metallic != mb->metallic || ma->roughness != mb->roughness ||
                       ma->emissive != mb->emissive || ma->albedoTexture != mb->albedoTexture)) ||
               da.castShadow != db.castShadow;
      break;
    }
    case ItemKind::Terrain: {
      const TerrainMesh& ta = a.terrains[ia.index];
      const TerrainMesh& tb = b.terrains[ib.index];
      c.moved = c.moved || ta.positions != tb.positions;
      c.look = ta.colors != tb.colors || colorOf(a, ta.material) != colorOf(b, tb.material);
      break;
    }
    case ItemKind::Instanced: {
      const Instanced& ba = a.instanced[ia.index];
      const Instanced& bb = b.instanced[ib.index];
      bool same = ba.worlds.size() == bb.worlds.size();
      for (std::size_t i = 0; same && i < ba.worlds.size(); ++i) same = near(ba.worlds[i].matrix(), bb.worlds[i].matrix());
      c.moved = c.moved || !same || ba.shape != bb.shape || ba.meshPath != bb.meshPath;
      c.look = ba.colors != bb.colors || colorOf(a, ba.material) != colorOf(b, bb.material);
      break;
    }
    case ItemKind::Points: {
      const PointBatch& pa = a.pointClouds[ia.index];
      const PointBatch& pb = b.pointClouds[ib.index];
      c.moved = c.moved || pa.points != pb.points;
      c.look = pa.colors != pb.colors || pa.pointSize != pb.pointSize;
      break;
    }
  }
  return c;
}

// The parts a record of one side is drawn as: those of its segment (the
// record itself), of its line (a compound child), of its material, or of
// the records drawn through it (`users`: a robot file's robots).
std::vector<std::size_t> partsOf(const std::vector<Item>& items, std::uint32_t line, const Referrers& users) {
  std::vector<std::size_t> out;
  if (line == 0) return out;
  std::set<std::uint32_t> through;
  for (auto [it, end] = users.equal_range(line); it != end; ++it) through.insert(it->second);
  for (std::size_t i = 0; i < items.size(); ++i)
    if (items[i].recordLine == line || items[i].partLine == line || items[i].materialLine == line ||
        through.count(items[i].recordLine))
      out.push_back(i);
  return out;
}

}  // namespace

std::vector<Item> assignItemIds(RenderScene& scene) {
  std::vector<Item> items;
  for (std::size_t i = 0; i < scene.drawables.size(); ++i) {
    const Drawable& d = scene.drawables[i];
    std::uint32_t record = segmentLine(scene, d.segment);
    std::uint32_t part = d.file.empty() && d.line ? d.line : record;
    items.push_back({ItemKind::Drawable, i, record, part, materialLine(scene, d.material), d.bounds,
                     d.shape == Shape::Ground});
  }
  for (std::size_t i = 0; i < scene.terrains.size(); ++i) {
    const TerrainMesh& t = scene.terrains[i];
    std::uint32_t record = segmentLine(scene, t.segment);
    items.push_back({ItemKind::Terrain, i, record, record, materialLine(scene, t.material), t.bounds});
  }
  for (std::size_t i = 0; i < scene.instanced.size(); ++i) {
    const Instanced& b = scene.instanced[i];
    std::uint32_t record = b.line ? b.line : segmentLine(scene, b.segment);
    items.push_back({ItemKind::Instanced, i, segmentLine(scene, b.segment), record, materialLine(scene, b.material),
                     b.bounds});
  }
  for (std::size_t i = 0; i < scene.pointClouds.size(); ++i) {
    const PointBatch& p = scene.pointClouds[i];
    std::uint32_t record = segmentLine(scene, p.segment);
    items.push_back({ItemKind::Points, i, record, record, 0, p.bounds});
  }
  // One segment per part, its color the part's id.
  scene.segments.assign(items.size(), Segment{});
  for (std::size_t i = 0; i < items.size(); ++i) {
    std::uint32_t id = static_cast<std::uint32_t>(i + 1);
    Segment& s = scene.segments[i];
    s.rgb[0] = std::uint8_t(id >> 16), s.rgb[1] = std::uint8_t(id >> 8), s.rgb[2] = std::uint8_t(id);
    int index = static_cast<int>(i);
    switch (items[i].kind) {
      case ItemKind::Drawable: scene.drawables[items[i].index].segment = index; break;
      case ItemKind::Terrain: scene.terrains[items[i].index].segment = index; break;
      case ItemKind::Instanced: scene.instanced[items[i].index].segment = index; break;
      case ItemKind::Points: scene.pointClouds[items[i].index].segment = index; break;
    }
  }
  return items;
}

int itemAt(const Image& ids, int x, int y, std::size_t items) {
  const std::uint8_t* p = ids.pixel(x, y);
  std::uint32_t id = (std::uint32_t(p[0]) << 16) | (std::uint32_t(p[1]) << 8) | p[2];
  return id == 0 || id > items ? -1 : int(id - 1);
}

Marks markChanges(const DiffResult& diff, const RenderScene& oldScene, const std::vector<Item>& oldItems,
                  const RenderScene& newScene, const std::vector<Item>& newItems, const Referrers& oldUsers,
                  const Referrers& newUsers) {
  Marks m;
  m.oldSide.assign(oldItems.size(), Mark::None);
  m.newSide.assign(newItems.size(), Mark::None);
  for (const Item& i : oldItems) m.oldGround.push_back(i.ground);
  for (const Item& i : newItems) m.newGround.push_back(i.ground);
  auto mark = [&](std::vector<Mark>& side, const std::vector<Item>& items, std::size_t i, Mark what) {
    // Added and removed win over changed (a record added whose material
    // also changed is added).
    if (side[i] == Mark::None || what == Mark::Added || what == Mark::Removed) side[i] = what;
    if (!items[i].ground && !items[i].bounds.isEmpty() && items[i].bounds.min().allFinite() && items[i].bounds.max().allFinite()) m.bounds.extend(items[i].bounds);
  };
  for (const RecordDiff& r : diff.records) {
    std::vector<std::size_t> before = r.change == Change::Added ? std::vector<std::size_t>{} : partsOf(oldItems, r.oldLine, oldUsers);
    std::vector<std::size_t> after = r.change == Change::Removed ? std::vector<std::size_t>{} : partsOf(newItems, r.newLine, newUsers);
    if (before.empty() && after.empty()) {
      ++m.undrawn;
      continue;
    }
    if (r.change == Change::Added) {
      ++m.added;
      for (std::size_t i : after) mark(m.newSide, newItems, i, Mark::Added);
      continue;
    }
    if (r.change == Change::Removed) {
      ++m.removed;
      for (std::size_t i : before) mark(m.oldSide, oldItems, i, Mark::Removed);
      continue;
    }
    ++m.changed;
    if (before.size() == after.size()) {
      // Part by part: a robot's links, a compound's children.
      bool any = false;
      std::vector<PartChange> changes;
      for (std::size_t k = 0; k < before.size(); ++k) {
        changes.push_back(compare(oldScene, oldItems[before[k]], newScene, newItems[after[k]]));
        any = any || changes.back().moved || changes.back().look;
      }
      for (std::size_t k = 0; k < before.size(); ++k) {
        if (any && !changes[k].moved && !changes[k].look) continue;
        mark(m.newSide, newItems, after[k], Mark::Changed);
        if (changes[k].moved) mark(m.oldSide, oldItems, before[k], Mark::Ghost);
      }
    } else {
      for (std::size_t i : after) mark(m.newSide, newItems, i, Mark::Changed);
      for (std::size_t i : before) mark(m.oldSide, oldItems, i, Mark::Ghost);
    }
  }
  return m;
}

Camera frameBox(const Eigen::AlignedBox3d& box, double aspect) {
  RenderScene framed;
  framed.bounds = box;
  return autoCamera(framed, aspect);
}

}  // namespace rscene::render::review
