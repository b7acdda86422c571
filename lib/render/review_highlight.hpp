// What rscene-diff --review draws: the scene's parts given ids for the
// renderer's segmentation pass (one flat color per drawable, terrain,
// instance batch and point cloud, so a pixel says exactly which part it
// shows), the changed records of a diff marked on those parts, a camera
// framing them, and changes.png composed from the new scene's colour image
// and both scenes' id images (never by comparing colours).
#pragma once
#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/diff.hpp"
#include "render/image.hpp"
#include "render/render_scene.hpp"

namespace rscene::render::review {

enum class ItemKind : std::uint8_t { Drawable, Terrain, Instanced, Points };

// One part of a RenderScene the id pass tells apart; its id is its index
// in the list plus one (24 bits; 0 is the background).
struct Item {
  ItemKind kind = ItemKind::Drawable;
  std::size_t index = 0;          // into drawables, terrains, instanced or pointClouds
  std::uint32_t recordLine = 0;   // the record it is drawn for (its segment's line)
  std::uint32_t partLine = 0;     // a compound child's own line; else recordLine
  std::uint32_t materialLine = 0; // its material record's line (0: engine default or a robot file's)
  Eigen::AlignedBox3d bounds;
  bool ground = false;  // a ground plane: never framed (as RenderScene::bounds leaves it out)
};

// The parts of `scene`, and its segments replaced by one per part whose
// color is the part's id: the segmentation pass then draws ids.  Call
// before the renderer is created (it packs segment colors at upload).
std::vector<Item> assignItemIds(RenderScene& scene);

// The part a segmentation pixel shows: its index into the items, -1 for
// the background (or a color that is no id).
int itemAt(const Image& ids, int x, int y, std::size_t items);

enum class Mark : std::uint8_t { None, Added, Removed, Changed, Ghost };

// What a diff makes of each part: on the new side Added and Changed, on the
// old side Removed and Ghost (a changed part whose old pose or shape
// differs: drawn as an outline where it stood).  A changed record drawn as
// several parts (a robot's links, a compound's children) marks only the
// parts whose pose or look changed when some did (a joint angle marks the
// links it moves), else all of them.  `undrawn`: changed records that mark
// no part (lights, environment, cameras ...).
struct Marks {
  std::vector<Mark> oldSide, newSide;
  std::vector<std::uint8_t> oldGround, newGround;  // per part: a ground plane (filled lightly)
  std::size_t added = 0, removed = 0, changed = 0, undrawn = 0;  // records
  Eigen::AlignedBox3d bounds;  // world bounds of every marked part, both sides
};
// A record's line -> the lines of the records drawn through it: an
// articulated_resource -> the articulated records that use it, so that a
// changed robot file marks those robots.
using Referrers = std::multimap<std::uint32_t, std::uint32_t>;
Marks markChanges(const DiffResult& diff, const RenderScene& oldScene, const std::vector<Item>& oldItems,
                  const RenderScene& newScene, const std::vector<Item>& newItems, const Referrers& oldUsers = {},
                  const Referrers& newUsers = {});

// The automatic view (autoCamera(), a three-quarter view) framing `box`.
Camera frameBox(const Eigen::AlignedBox3d& box, double aspect);

// The colors changes.png uses (also the legend's and review pages').
struct Palette {
  static constexpr std::uint8_t added[3] = {30, 200, 60};
  static constexpr std::uint8_t removed[3] = {230, 30, 30};
  static constexpr std::uint8_t changed[3] = {255, 140, 0};
  static constexpr std::uint8_t ghost[3] = {40, 120, 255};
};

// changes.png: `color` (the new scene) faded to grey, the new side's marked
// parts filled and outlined (added green, changed orange), the old side's
// removed parts red where they stood and changed parts' old places as a
// dashed blue outline; below the picture a legend band saying what each
// color means with the counts, and how many changed records draw nothing.
// `oldColor` (the old scene, optional): removed parts are drawn from it
// where the new scene shows nothing there.  All images the same size.
Image composeChanges(const Image& color, const Image& newIds, const Image& oldIds, const Marks& marks,
                     const Image* oldColor = nullptr);

// Height of one line of the legend band composeChanges() adds below an
// image of height `h` (more lines when its entries do not fit the width).
int legendHeight(int width, int height);

// Draws `text` (printable ASCII, a 5x7 font with descenders: 9 rows) at
// (x, y) scaled by `scale`.
void drawText(Image& image, int x, int y, const std::string& text, const std::uint8_t rgb[3], int scale);
int textWidth(const std::string& text, int scale);

}  // namespace rscene::render::review
