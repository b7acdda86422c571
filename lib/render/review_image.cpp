// changes.png of rscene-diff --review (review_highlight.hpp): the marked
// parts painted over the new scene, and the legend band with a 5x7 font.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "render/review_highlight.hpp"

namespace rscene::render::review {
namespace {

// 5x7 glyphs on a 9-row cell, a row per byte (bit 4 the leftmost column):
// rows 0-6 down to the baseline, 7-8 for the descenders of g, j, p, q, y
// (squeezed above the baseline they read as 9, i and rho).
constexpr int kGlyphRows = 9;
struct Glyph {
  char c;
  std::array<std::uint8_t, kGlyphRows> rows;
};
constexpr Glyph kFont[] = {
    {'a', {0x00, 0x00, 0x0E, 0x01, 0x0F, 0x11, 0x0F}}, {'b', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x1E}},
    {'c', {0x00, 0x00, 0x0E, 0x10, 0x10, 0x11, 0x0E}}, {'d', {0x01, 0x01, 0x0D, 0x13, 0x11, 0x11, 0x0F}},
    {'e', {0x00, 0x00, 0x0E, 0x11, 0x1F, 0x10, 0x0E}}, {'f', {0x06, 0x09, 0x08, 0x1C, 0x08, 0x08, 0x08}},
    {'g', {0x00, 0x00, 0x0F, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x0E}}, {'h', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'i', {0x04, 0x00, 0x0C, 0x04, 0x04, 0x04, 0x0E}}, {'j', {0x02, 0x00, 0x06, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'k', {0x10, 0x10, 0x12, 0x14, 0x18, 0x14, 0x12}}, {'l', {0x0C, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'m', {0x00, 0x00, 0x1A, 0x15, 0x15, 0x11, 0x11}}, {'n', {0x00, 0x00, 0x16, 0x19, 0x11, 0x11, 0x11}},
    {'o', {0x00, 0x00, 0x0E, 0x11, 0x11, 0x11, 0x0E}}, {'p', {0x00, 0x00, 0x1E, 0x11, 0x11, 0x11, 0x1E, 0x10, 0x10}},
    {'q', {0x00, 0x00, 0x0F, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x01}}, {'r', {0x00, 0x00, 0x16, 0x19, 0x10, 0x10, 0x10}},
    {'s', {0x00, 0x00, 0x0E, 0x10, 0x0E, 0x01, 0x1E}}, {'t', {0x08, 0x08, 0x1C, 0x08, 0x08, 0x09, 0x06}},
    {'u', {0x00, 0x00, 0x11, 0x11, 0x11, 0x13, 0x0D}}, {'v', {0x00, 0x00, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'w', {0x00, 0x00, 0x11, 0x11, 0x15, 0x15, 0x0A}}, {'x', {0x00, 0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11}},
    {'y', {0x00, 0x00, 0x11, 0x11, 0x11, 0x11, 0x0F, 0x01, 0x0E}}, {'z', {0x00, 0x00, 0x1F, 0x02, 0x04, 0x08, 0x1F}},
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}}, {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
    {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}}, {',', {0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}}, {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {'+', {0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00}}, {'/', {0x01, 0x02, 0x02, 0x04, 0x08, 0x08, 0x10}},
};

const Glyph* glyph(char c) {
  if (c >= 'A' && c <= 'Z') c = char(c - 'A' + 'a');
  for (const Glyph& g : kFont)
    if (g.c == c) return &g;
  return nullptr;
}

void put(Image& im, int x, int y, const std::uint8_t rgb[3]) {
  if (x < 0 || y < 0 || x >= im.width || y >= im.height) return;
  std::uint8_t* p = im.pixel(x, y);
  p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
}

void fillRect(Image& im, int x0, int y0, int w, int h, const std::uint8_t rgb[3]) {
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) put(im, x, y, rgb);
}

std::uint8_t mix(std::uint8_t a, std::uint8_t b, float t) { return std::uint8_t(std::lround(a + (b - a) * t)); }

// One category's mask over the image: the part (its index + 1) each pixel
// shows when that part is so marked, else 0.  `ground`: only the parts
// that are (1) or are not (0) ground planes; -1 both.
using Mask = std::vector<std::uint32_t>;
Mask maskOf(const Image& ids, const std::vector<Mark>& marks, const std::vector<std::uint8_t>& grounds, Mark what,
            int ground = -1) {
  Mask mask(std::size_t(ids.width) * ids.height, 0);
  for (int y = 0; y < ids.height; ++y)
    for (int x = 0; x < ids.width; ++x) {
      int i = itemAt(ids, x, y, marks.size());
      if (i < 0 || marks[std::size_t(i)] != what) continue;
      bool isGround = std::size_t(i) < grounds.size() && grounds[std::size_t(i)];
      if (ground >= 0 && isGround != (ground == 1)) continue;
      mask[std::size_t(y) * ids.width + x] = std::uint32_t(i) + 1;
    }
  return mask;
}

bool any(const Mask& mask) {
  return std::any_of(mask.begin(), mask.end(), [](std::uint32_t v) { return v != 0; });
}

// Fills the mask's pixels mixed with `rgb` by `amount`, then paints its
// edge (pixels of the mask within `thick` of one outside it, of another
// part, or of the image's border) in `rgb` itself: each part is outlined,
// so crates standing on a removed floor stay apart from it.  `dash` > 0
// paints every other run of `dash` pixels of the edge only.
void paint(Image& im, const Mask& mask, const std::uint8_t rgb[3], float amount, int thick, int dash) {
  const int w = im.width, h = im.height;
  auto at = [&](int x, int y) -> std::uint32_t {
    return x >= 0 && y >= 0 && x < w && y < h ? mask[std::size_t(y) * w + x] : 0;
  };
  auto in = [&](int x, int y) { return at(x, y) != 0; };
  std::vector<std::uint8_t> edge(mask.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint32_t part = at(x, y);
      if (!part) continue;
      bool e = false;
      for (int d = 1; d <= thick && !e; ++d)
        e = at(x - d, y) != part || at(x + d, y) != part || at(x, y - d) != part || at(x, y + d) != part;
      edge[std::size_t(y) * w + x] = e;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!in(x, y)) continue;
      std::uint8_t* p = im.pixel(x, y);
      if (edge[std::size_t(y) * w + x]) {
        if (dash > 0 && ((x + y) / dash) % 2) continue;
        p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2], p[3] = 255;
      } else if (amount > 0) {
        for (int k = 0; k < 3; ++k) p[k] = mix(p[k], rgb[k], amount);
      }
    }
}

}  // namespace

int textWidth(const std::string& text, int scale) { return int(text.size()) * 6 * scale; }

void drawText(Image& image, int x, int y, const std::string& text, const std::uint8_t rgb[3], int scale) {
  for (std::size_t n = 0; n < text.size(); ++n) {
    const Glyph* g = glyph(text[n]);
    if (!g) continue;  // a space, or a character the font lacks
    int gx = x + int(n) * 6 * scale;
    for (int r = 0; r < kGlyphRows; ++r)
      for (int c = 0; c < 5; ++c)
        if (g->rows[std::size_t(r)] & (0x10 >> c)) fillRect(image, gx + c * scale, y + r * scale, scale, scale, rgb);
  }
}

int legendHeight(int width, int height) {
  int scale = std::max(1, std::min(width / 320, height / 180));
  return 11 * scale;
}

Image composeChanges(const Image& color, const Image& newIds, const Image& oldIds, const Marks& marks,
                     const Image* oldColor) {
  const int w = color.width, h = color.height;
  const int scale = std::max(1, std::min(w / 320, h / 180));
  // A scene faded to a light grey: what is marked stands out.
  auto fade = [](const std::uint8_t* s, std::uint8_t* d) {
    float grey = 0.299f * s[0] + 0.587f * s[1] + 0.114f * s[2];
    for (int k = 0; k < 3; ++k) d[k] = std::uint8_t(std::lround(0.25f * s[k] + 0.45f * grey + 0.30f * 200.0f));
  };
  Image picture;
  picture.width = w, picture.height = h;
  picture.rgba.assign(std::size_t(w) * h * 4, 255);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) fade(color.pixel(x, y), picture.pixel(x, y));
  const int thick = std::max(1, scale);
  bool sized = oldIds.width == w && oldIds.height == h;
  // An id image of another size (none drawn) marks nothing.
  const bool newSized = newIds.width == w && newIds.height == h;
  const Mask none(std::size_t(w) * h, 0);
  auto masked = [&](bool drawn, const Image& ids, const std::vector<Mark>& side, const std::vector<std::uint8_t>& grounds,
                    Mark what, int ground) { return drawn ? maskOf(ids, side, grounds, what, ground) : none; };
  Mask ghost = masked(sized, oldIds, marks.oldSide, marks.oldGround, Mark::Ghost, -1);
  // Ground planes are filled lightly: an added or removed floor would
  // otherwise flood the picture; their outline still says it.
  Mask removed = masked(sized, oldIds, marks.oldSide, marks.oldGround, Mark::Removed, 0);
  Mask removedGround = masked(sized, oldIds, marks.oldSide, marks.oldGround, Mark::Removed, 1);
  Mask added = masked(newSized, newIds, marks.newSide, marks.newGround, Mark::Added, 0);
  Mask addedGround = masked(newSized, newIds, marks.newSide, marks.newGround, Mark::Added, 1);
  Mask changed = masked(newSized, newIds, marks.newSide, marks.newGround, Mark::Changed, -1);
  // A removed part where the new scene shows nothing is drawn as it
  // looked (the old scene's colours, faded), so it keeps its shading as
  // an added one does.
  if (oldColor && oldColor->width == w && oldColor->height == h)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::size_t i = std::size_t(y) * w + x;
        if ((removed[i] || removedGround[i]) && (!newSized || itemAt(newIds, x, y, marks.newSide.size()) < 0))
          fade(oldColor->pixel(x, y), picture.pixel(x, y));
      }
  paint(picture, ghost, Palette::ghost, 0.15f, thick, 3 * thick);
  paint(picture, removedGround, Palette::removed, 0.2f, thick, 0);
  paint(picture, addedGround, Palette::added, 0.2f, thick, 0);
  paint(picture, removed, Palette::removed, 0.55f, thick, 0);
  paint(picture, changed, Palette::changed, 0.55f, thick, 0);
  paint(picture, added, Palette::added, 0.55f, thick, 0);

  // The legend: a swatch and a word for each kind of mark shown, on as
  // many lines as the width needs.
  struct Entry {
    const std::uint8_t* rgb;
    std::string text;
    bool dashed;
    int width;
  };
  std::vector<Entry> entries;
  auto entry = [&](const std::uint8_t* rgb, const std::string& text, bool dashed) {
    entries.push_back({rgb, text, dashed, (rgb ? 9 * scale : 0) + textWidth(text, scale) + 4 * scale});
  };
  auto count = [](std::size_t n) { return " " + std::to_string(n); };
  if (marks.added) entry(Palette::added, "added" + count(marks.added), false);
  if (marks.removed) entry(Palette::removed, "removed" + count(marks.removed), false);
  if (marks.changed) entry(Palette::changed, "changed" + count(marks.changed), false);
  if (sized && any(ghost)) entry(Palette::ghost, "old place", true);
  if (marks.undrawn)
    entry(nullptr, "+" + std::to_string(marks.undrawn) + " not drawn: see the table", false);
  if (!marks.added && !marks.removed && !marks.changed && !marks.undrawn) entry(nullptr, "no change", false);
  const int lineHeight = legendHeight(w, h);
  std::vector<int> lineOf;
  int lines = 1;
  for (int x = 2 * scale; const Entry& e : entries) {
    if (x > 2 * scale && x + e.width > w) {
      ++lines;
      x = 2 * scale;
    }
    lineOf.push_back(lines - 1);
    x += e.width;
  }
  Image out;
  out.width = w;
  out.height = h + lines * lineHeight;
  out.rgba.assign(std::size_t(w) * out.height * 4, 255);
  std::copy(picture.rgba.begin(), picture.rgba.end(), out.rgba.begin());
  const std::uint8_t ink[3] = {40, 40, 40};
  const std::uint8_t paper[3] = {245, 245, 245};
  fillRect(out, 0, h, w, lines * lineHeight, paper);
  int x = 2 * scale, line = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Entry& e = entries[i];
    if (lineOf[i] != line) line = lineOf[i], x = 2 * scale;
    int y = h + line * lineHeight + 2 * scale;
    if (e.rgb) {
      for (int yy = 0; yy < 7 * scale; ++yy)
        for (int xx = 0; xx < 7 * scale; ++xx) {
          bool border = xx < scale || yy < scale || xx >= 6 * scale || yy >= 6 * scale;
          if (e.dashed && (!border || ((xx + yy) / (2 * scale)) % 2)) continue;
          const std::uint8_t light[3] = {mix(paper[0], e.rgb[0], 0.55f), mix(paper[1], e.rgb[1], 0.55f),
                                         mix(paper[2], e.rgb[2], 0.55f)};
          // Swatches in the fill's mixed color with a border one step
          // darker than the outlines', so that the exact outline colors
          // appear only on the scene's parts.
          const std::uint8_t dark[3] = {mix(e.rgb[0], 0, 0.2f), mix(e.rgb[1], 0, 0.2f), mix(e.rgb[2], 0, 0.2f)};
          put(out, x + xx, y + yy, border ? dark : light);
        }
    }
    drawText(out, x + (e.rgb ? 9 * scale : 0), y, e.text, ink, scale);
    x += e.width;
  }
  return out;
}

}  // namespace rscene::render::review
