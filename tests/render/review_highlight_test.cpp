// rscene-diff --review's marking (lib/render/review_highlight.hpp): the
// parts given ids, a diff's records marked on them, the framing camera and
// changes.png's composition.  Data only: images are made by hand here
// (the drawn ones are tested in shell-tests/diff_review.bats).
#include "render/review_highlight.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/loader.hpp"

using namespace rscene;
using namespace rscene::render;
using namespace rscene::render::review;

namespace {

const char* kHeader = "raisim_engine_scene 2\n"
                      "material mat_a 0.5 0.5 0.5 1 0 0.5 0 0 0 0 false - - - - - - id=mat_a\n"
                      "light /World/Sun 0.3 0.2 -1 3 type=directional\n";
std::string box(const char* name, const char* xyz, const char* material = "-") {
  return std::string("object /World/") + name + " box " + xyz + " 1 0 0 0 1 1 1 1 1 1 default " + material +
         " false true false - static true 1 18446744073709551615\n";
}

struct Side {
  LoadResult loaded;
  RenderScene scene;
  std::vector<Item> items;
};

void build(Side& s, const std::string& text) {
  s.loaded = parse(text);
  ASSERT_TRUE(s.loaded.ok());
  Diagnostics diags;
  ASSERT_TRUE(buildRenderScene(s.loaded.document, SceneOptions{}, s.scene, diags));
  s.items = assignItemIds(s.scene);
}

Marks marksOf(Side& a, Side& b) {
  DiffResult d = diff(a.loaded.document, b.loaded.document);
  return markChanges(d, a.scene, a.items, b.scene, b.items);
}

std::size_t itemOf(const Side& s, const std::string& path) {
  // The record's line, found in the text; its part is the item of that line.
  const std::string& text = s.loaded.document.buffer();
  std::size_t at = text.find(path + " ");
  if (at == std::string::npos) {
    ADD_FAILURE() << path << " is not in the scene";
    return 0;
  }
  std::uint32_t line = 1 + std::uint32_t(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n'));
  for (std::size_t i = 0; i < s.items.size(); ++i)
    if (s.items[i].recordLine == line) return i;
  ADD_FAILURE() << "no part drawn for " << path;
  return 0;
}

}  // namespace

TEST(ReviewIds, EveryPartGetsItsOwnIdColor) {
  Side s;
  build(s, std::string(kHeader) + box("A", "0 0 0.5") + box("B", "2 0 0.5"));
  ASSERT_EQ(s.items.size(), 2u);
  ASSERT_EQ(s.scene.segments.size(), 2u);
  for (std::size_t i = 0; i < s.items.size(); ++i) {
    const Segment& g = s.scene.segments[std::size_t(s.scene.drawables[s.items[i].index].segment)];
    Image one{1, 1, {g.rgb[0], g.rgb[1], g.rgb[2], 255}};
    EXPECT_EQ(itemAt(one, 0, 0, s.items.size()), int(i));
  }
  Image background{1, 1, {0, 0, 0, 255}};
  EXPECT_EQ(itemAt(background, 0, 0, s.items.size()), -1);
  Image stranger{1, 1, {0, 0, 9, 255}};  // no part has id 9
  EXPECT_EQ(itemAt(stranger, 0, 0, s.items.size()), -1);
}

TEST(ReviewMarks, MovedAddedRemovedAndUndrawn) {
  Side a, b;
  build(a, std::string(kHeader) + box("Moved", "0 0 0.5") + box("Gone", "-2 0 0.5") + box("Still", "0 3 0.5"));
  std::string text = std::string(kHeader) + box("Moved", "1.5 0 0.5") + box("Still", "0 3 0.5") +
                     box("New", "3 3 0.5");
  text.replace(text.find("light /World/Sun 0.3 0.2 -1 3"), 29, "light /World/Sun 0.3 0.2 -1 4");
  build(b, text);
  Marks m = marksOf(a, b);
  EXPECT_EQ(m.changed, 1u);
  EXPECT_EQ(m.added, 1u);
  EXPECT_EQ(m.removed, 1u);
  EXPECT_EQ(m.undrawn, 1u);  // the light
  EXPECT_EQ(m.newSide[itemOf(b, "/World/Moved")], Mark::Changed);
  EXPECT_EQ(m.oldSide[itemOf(a, "/World/Moved")], Mark::Ghost);
  EXPECT_EQ(m.oldSide[itemOf(a, "/World/Gone")], Mark::Removed);
  EXPECT_EQ(m.newSide[itemOf(b, "/World/New")], Mark::Added);
  EXPECT_EQ(m.newSide[itemOf(b, "/World/Still")], Mark::None);
  EXPECT_EQ(m.oldSide[itemOf(a, "/World/Still")], Mark::None);
  // The framed bounds: the moved box both places, the removed and the added ones.
  EXPECT_TRUE(m.bounds.contains(Eigen::Vector3d(-2, 0, 0.5)));
  EXPECT_TRUE(m.bounds.contains(Eigen::Vector3d(3, 3, 0.5)));
  EXPECT_LT(m.bounds.min().y(), -0.4);
}

TEST(ReviewMarks, RespelledIsNothingAndAMaterialMarksItsBodiesWithoutAGhost) {
  Side a, b, c;
  build(a, std::string(kHeader) + box("A", "0 0 0.5", "mat_a") + box("B", "2 0 0.5"));
  build(b, std::string(kHeader) + box("A", "0.0 0 0.50", "mat_a") + box("B", "2 0 0.5"));
  Marks same = marksOf(a, b);
  EXPECT_EQ(same.added + same.removed + same.changed + same.undrawn, 0u);
  for (Mark k : same.newSide) EXPECT_EQ(k, Mark::None);
  std::string text = std::string(kHeader) + box("A", "0 0 0.5", "mat_a") + box("B", "2 0 0.5");
  text.replace(text.find("mat_a 0.5 0.5 0.5"), 17, "mat_a 0.9 0.1 0.1");
  build(c, text);
  Marks m = marksOf(a, c);
  EXPECT_EQ(m.changed, 1u);
  EXPECT_EQ(m.newSide[itemOf(c, "/World/A")], Mark::Changed);
  EXPECT_EQ(m.newSide[itemOf(c, "/World/B")], Mark::None);
  for (Mark k : m.oldSide) EXPECT_EQ(k, Mark::None);  // nothing moved: no old place drawn
}

TEST(ReviewFraming, TheCameraLooksAtTheBoxFromTheFrontLeftAndSeesItAll) {
  Eigen::AlignedBox3d box(Eigen::Vector3d(4, 4, 0), Eigen::Vector3d(5, 5, 1));
  Camera c = frameBox(box, 16.0 / 9);
  Eigen::Vector3d forward = c.world.orientation * Eigen::Vector3d::UnitX();
  Eigen::Vector3d toCenter = (box.center() - c.world.position).normalized();
  EXPECT_GT(forward.dot(toCenter), 0.999);
  EXPECT_LT(c.world.position.x(), 4);
  EXPECT_LT(c.world.position.y(), 4);
  EXPECT_GT(c.world.position.z(), 0.5);
}

TEST(ReviewImage, MarksAreFilledAndOutlinedInExactColorsAndTheLegendGoesBelow) {
  const int w = 12, h = 8;
  Image color{w, h, std::vector<std::uint8_t>(std::size_t(w) * h * 4, 128)};
  Image ids{w, h, std::vector<std::uint8_t>(std::size_t(w) * h * 4, 0)};
  Image oldIds = ids;
  // Part 0 (id 1) covers x 2..5 in the new scene, part 0 of the old one
  // x 6..9 (a ghost), rows 2..5.
  for (int y = 2; y <= 5; ++y) {
    for (int x = 2; x <= 5; ++x) ids.pixel(x, y)[2] = 1;
    for (int x = 6; x <= 9; ++x) oldIds.pixel(x, y)[2] = 1;
  }
  Marks m;
  m.newSide = {Mark::Changed};
  m.oldSide = {Mark::Ghost};
  m.changed = 1;
  Image out = composeChanges(color, ids, oldIds, m);
  ASSERT_EQ(out.width, w);
  // Two entries (changed, old place), each wider than 12 pixels: two lines.
  EXPECT_EQ(out.height, h + 2 * legendHeight(w, h));
  auto is = [&](int x, int y, const std::uint8_t* rgb) {
    const std::uint8_t* p = out.pixel(x, y);
    return p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2];
  };
  EXPECT_TRUE(is(2, 2, Palette::changed));   // the edge
  EXPECT_FALSE(is(3, 3, Palette::changed));  // inside: a mix of grey and orange
  EXPECT_GT(out.pixel(3, 3)[0], out.pixel(3, 3)[2]);
  EXPECT_FALSE(is(0, 0, Palette::changed));
  int ghost = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 6; x <= 9; ++x) ghost += is(x, y, Palette::ghost);
  EXPECT_GT(ghost, 2);
  EXPECT_LT(ghost, 12);  // dashed: not the whole edge
  // Nothing marked: the picture is the faded scene alone, no palette color.
  Marks none;
  none.newSide = {Mark::None};
  none.oldSide = {Mark::None};
  Image plain = composeChanges(color, ids, oldIds, none);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) EXPECT_EQ(plain.pixel(x, y)[0], plain.pixel(0, 0)[0]);
}

TEST(ReviewImage, IdImagesOfAnotherSizeMarkNothing) {
  Image color{4, 3, std::vector<std::uint8_t>(4 * 3 * 4, 100)};
  Marks m;
  m.newSide = {Mark::Added};
  m.oldSide = {Mark::Removed};
  m.added = m.removed = 1;
  Image out = composeChanges(color, Image{}, Image{}, m);  // no id image drawn
  ASSERT_EQ(out.width, 4);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) EXPECT_EQ(out.pixel(x, y)[0], out.pixel(0, 0)[0]);
}

// A deleted scene: the removed floor and a crate on it.  The floor is
// filled lightly (it would flood the picture), the crate fully; each part
// keeps its own outline, so the crate stands apart from the floor; where
// the new scene shows nothing, the old scene's shading is under the red.
TEST(ReviewImage, ARemovedFloorIsFilledLightlyAndEachRemovedPartOutlinedOnTheOldShading) {
  const int w = 16, h = 10;
  Image color{w, h, std::vector<std::uint8_t>(std::size_t(w) * h * 4, 200)};  // the new scene: empty grey
  Image oldColor = color;
  for (int x = 0; x < w; ++x) oldColor.pixel(x, 8)[0] = oldColor.pixel(x, 8)[1] = oldColor.pixel(x, 8)[2] = 40;  // a dark row
  Image none{w, h, std::vector<std::uint8_t>(std::size_t(w) * h * 4, 0)};
  Image oldIds = none;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) oldIds.pixel(x, y)[2] = (x >= 5 && x <= 10 && y >= 3 && y <= 6) ? 2 : 1;
  Marks m;
  m.oldSide = {Mark::Removed, Mark::Removed};
  m.oldGround = {1, 0};  // part 0 (id 1): the floor
  m.newSide = {};
  m.removed = 2;
  Image out = composeChanges(color, none, oldIds, m, &oldColor);
  auto red = [&](int x, int y) {
    const std::uint8_t* p = out.pixel(x, y);
    return p[0] == Palette::removed[0] && p[1] == Palette::removed[1] && p[2] == Palette::removed[2];
  };
  // The crate's edge is red where it meets the floor, and the floor's too.
  EXPECT_TRUE(red(5, 4));
  EXPECT_TRUE(red(4, 4));
  // Inside the crate: strongly red; inside the floor: lightly.
  const std::uint8_t* crate = out.pixel(7, 4);
  const std::uint8_t* floor = out.pixel(2, 4);
  EXPECT_GT(int(crate[0]) - int(crate[1]), 60);
  EXPECT_GT(int(floor[0]) - int(floor[1]), 5);
  EXPECT_LT(int(floor[0]) - int(floor[1]), 60);
  // The old scene's dark row shows through the floor's light fill.
  EXPECT_LT(out.pixel(2, 8)[1] + 40, out.pixel(2, 5)[1]);
}
