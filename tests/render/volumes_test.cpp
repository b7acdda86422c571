// Decals, irradiance volumes and fog on the CPU backend (VolumeEffects,
// shader_volumes.cpp): a decal paints its box's footprint and nothing else
// and fades at its edges; its texture lands upright; a missing texture is
// RS5001; a fog sphere tints what is behind it the more the longer the
// path inside, and nothing outside; height fog is thicker near its base;
// an irradiance volume brightens what is inside it only.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "gl_test_context.hpp"
#include "asset/image.hpp"
#include "core/loader.hpp"
#include "render/view.hpp"

using namespace rscene;
using namespace rscene::render;

namespace {

// Plain black background, a dim light from straight above, no shadows, a
// white floor slab whose top is z = 0.
const char* kHeader =
    "raisim_engine_scene 1\n"
    "environment 0 0 0 0.1 0.1 0.1 0 false true 10 - backgroundMode=plain_color colorMode=fast_linear exposure=1 "
    "%s\n"
    "material white 0.8 0.8 0.8 1 0 0.9 0 0 0 0 false - - - - - - id=white\n"
    "light /World/Sun 0 0 -1 2 type=directional shadows=false\n"
    "object /World/Floor box 0 0 -0.05 1 0 0 0 40 40 0.1 0.5 1 1 default white false true false - static true 1 "
    "18446744073709551615\n";

struct Built {
  RenderScene scene;
  Diagnostics diags;
  bool ok = false;
};

std::unique_ptr<Built> build(const std::string& body, const std::string& environmentKeys = "") {
  auto b = std::make_unique<Built>();
  char header[1024];
  std::snprintf(header, sizeof header, kHeader, environmentKeys.c_str());
  LoadResult loaded = parse(header + body);
  EXPECT_TRUE(loaded.ok());
  Scene model;
  b->ok = buildRenderScene(loaded.document, SceneOptions{}, model, b->scene, b->diags);
  EXPECT_TRUE(b->ok);
  return b;
}

constexpr int kSide = 200;
constexpr double kHeight = 10;  // of the top-down camera above the floor

// Straight down from (0, 0, 10), 60 degrees: world +x is up in the image,
// world +y to the left; 1 m on the floor is 17.3 px.
View topDown() {
  View v;
  v.name = "top";
  v.camera.width = kSide;
  v.camera.height = kSide;
  v.camera.verticalFov = 60;
  v.camera.nearPlane = 0.05;
  v.camera.farPlane = 100;
  v.camera.projection = "perspective";
  v.camera.enabled = true;
  v.camera.world.position = Eigen::Vector3d(0, 0, kHeight);
  v.camera.world.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  v.passes = {Pass::Color};
  return v;
}

double pixelsPerMetre() { return kSide / 2.0 / std::tan(M_PI / 6) / kHeight; }

// The pixel (column, row) that sees floor point (x, y).
std::pair<int, int> pixelOf(double x, double y) {
  double f = pixelsPerMetre();
  return {int(std::floor(kSide / 2.0 - f * y)), int(std::floor(kSide / 2.0 - f * x))};
}

void writeDebug(const Image& im, const std::string& name) {
  // Set RSCENE_TEST_IMAGES=DIR to look at what the tests render.
  if (const char* dir = std::getenv("RSCENE_TEST_IMAGES")) {
    std::string png = encodePng(im);
    if (FILE* f = std::fopen((std::string(dir) + "/" + name + ".png").c_str(), "wb")) {
      std::fwrite(png.data(), 1, png.size(), f);
      std::fclose(f);
    }
  }
}

Image draw(const RenderScene& scene, const View& v, const std::string& name, Diagnostics* diags = nullptr,
           RenderOptions options = {}) {
  ViewImages out;
  if (!context()) return out.color;
  Diagnostics local;
  Diagnostics& d = diags ? *diags : local;
  auto r = Renderer::create(scene, options, d);
  if (!r) return out.color;
  EXPECT_TRUE(r->render(v, out, d)) << (d.empty() ? "" : d.front().message);
  writeDebug(out.color, name);
  return out.color;
}

struct Rgb {
  int r, g, b;
};
Rgb at(const Image& im, std::pair<int, int> p) {
  const std::uint8_t* c = im.pixel(p.first, p.second);
  return {c[0], c[1], c[2]};
}
// How much redder than the floor's gray: 0 for gray, ~200 for the red decal.
int redness(Rgb c) { return c.r - (c.g + c.b) / 2; }
// A channel of the image (gamma 2.2 encoded) in linear light, 0..1.
double linear(int c) { return std::pow(c / 255.0, 2.2); }

std::string decal(const std::string& extra) {
  return "projected_decal /World/Decal 0 0 0 1 0 0 0 1 1 1 halfExtents=1,0.5,0.5 color=1,0,0,1 edgeFade=0 "
         "normalFade=0 upperFade=0 lowerFade=0 " +
         extra + "\n";
}

}  // namespace

TEST(Volumes, DecalPaintsItsFootprintAndNothingElse) {
  auto b = build(decal(""));
  EXPECT_EQ(b->scene.skipped.count("projected_decal"), 0u);  // drawn, not reported as skipped
  ASSERT_EQ(b->scene.decals.size(), 1u);
  Image im = draw(b->scene, topDown(), "decal_footprint");
  ASSERT_EQ(im.width, kSide);
  EXPECT_GT(redness(at(im, pixelOf(0, 0))), 150);
  EXPECT_GT(redness(at(im, pixelOf(0.9, 0.4))), 150);   // inside, near a corner
  EXPECT_LT(redness(at(im, pixelOf(0, 0.7))), 10);      // beyond the 0.5 m half width
  EXPECT_LT(redness(at(im, pixelOf(1.2, 0))), 10);      // beyond the 1 m half length
  // Every red pixel inside the 2 m x 1 m footprint (a pixel of slack), and
  // as many as the footprint covers.
  double f = pixelsPerMetre();
  int red = 0, outside = 0;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      if (redness(at(im, {x, y})) < 60) continue;
      ++red;
      double wx = (kSide / 2.0 - (y + 0.5)) / f, wy = (kSide / 2.0 - (x + 0.5)) / f;
      if (std::abs(wx) > 1 + 1 / f || std::abs(wy) > 0.5 + 1 / f) ++outside;
    }
  EXPECT_EQ(outside, 0);
  EXPECT_NEAR(red, 2 * f * f, 0.1 * 2 * f * f);
}

TEST(Volumes, DecalFadesAtItsEdges) {
  auto sharp = build(decal(""));
  auto faded = build(decal("edgeFade=0.5"));
  Image a = draw(sharp->scene, topDown(), "decal_sharp");
  Image b = draw(faded->scene, topDown(), "decal_faded");
  ASSERT_EQ(b.width, kSide);
  // At the centre both are full; 0.1 of the half width from the side the
  // faded one keeps about a fifth of its color.
  EXPECT_NEAR(redness(at(b, pixelOf(0, 0))), redness(at(a, pixelOf(0, 0))), 4);
  int edgeSharp = redness(at(a, pixelOf(0, 0.45))), edgeFaded = redness(at(b, pixelOf(0, 0.45)));
  EXPECT_GT(edgeSharp, 150);
  EXPECT_LT(edgeFaded, edgeSharp * 0.45);
  EXPECT_GT(edgeFaded, 5);
}

TEST(Volumes, DecalTextureLandsUprightAndAMissingOneIsAnError) {
  // 2x2: the top row red, the bottom row blue; the image's top is the
  // box's local +y (world +y here: the left of the view).
  Image tex;
  tex.width = 2;
  tex.height = 2;
  tex.rgba = {255, 0, 0, 255, 255, 0, 0, 255, 0, 0, 255, 255, 0, 0, 255, 255};
  auto dir = std::filesystem::temp_directory_path() / "rscene_volumes_test";
  std::filesystem::create_directories(dir);
  std::string path = (dir / "updown.png").string();
  {
    std::string png = encodePng(tex);
    FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_TRUE(f);
    std::fwrite(png.data(), 1, png.size(), f);
    std::fclose(f);
  }
  auto b = build("projected_decal /World/Decal 0 0 0 1 0 0 0 1 1 1 halfExtents=1,1,0.5 color=1,1,1,1 edgeFade=0 "
                 "normalFade=0 upperFade=0 lowerFade=0 albedoTexture=" +
                 path + "\n");
  Image im = draw(b->scene, topDown(), "decal_texture");
  ASSERT_EQ(im.width, kSide);
  Rgb left = at(im, pixelOf(0, 0.5)), right = at(im, pixelOf(0, -0.5));
  EXPECT_GT(left.r, left.b + 100);
  EXPECT_GT(right.b, right.r + 100);

  // Missing: RS5001, no renderer; allowed: a warning, the color drawn.
  auto missing = build(decal("albedoTexture=" + (dir / "absent.png").string()));
  if (!context()) return;
  Diagnostics d;
  EXPECT_FALSE(Renderer::create(missing->scene, {}, d));
  ASSERT_FALSE(d.empty());
  EXPECT_EQ(d.back().code, "RS5001");
  EXPECT_EQ(d.back().severity, Severity::Error);
  EXPECT_NE(d.back().message.find("absent.png"), std::string::npos);
  EXPECT_GT(d.back().column, 0u);
  RenderOptions allow;
  allow.allowMissingAssets = true;
  Diagnostics w;
  Image colorOnly = draw(missing->scene, topDown(), "decal_missing", &w, allow);
  ASSERT_EQ(colorOnly.width, kSide);
  ASSERT_FALSE(w.empty());
  EXPECT_EQ(w.front().code, "RS5001");
  EXPECT_EQ(w.front().severity, Severity::Warning);
  EXPECT_GT(redness(at(colorOnly, pixelOf(0, 0))), 150);
  std::filesystem::remove_all(dir);
}

TEST(Volumes, DecalFadesWithDistanceFromTheEye) {
  // The eye is 10 m away: begin 8, length 4 leaves half the color.
  auto near = build(decal("distanceFadeEnabled=true distanceFadeBegin=20 distanceFadeLength=4"));
  auto half = build(decal("distanceFadeEnabled=true distanceFadeBegin=8 distanceFadeLength=4"));
  auto gone = build(decal("distanceFadeEnabled=true distanceFadeBegin=2 distanceFadeLength=4"));
  int full = redness(at(draw(near->scene, topDown(), "decal_near"), pixelOf(0, 0)));
  int halfway = redness(at(draw(half->scene, topDown(), "decal_half"), pixelOf(0, 0)));
  int none = redness(at(draw(gone->scene, topDown(), "decal_gone"), pixelOf(0, 0)));
  EXPECT_GT(full, 150);
  EXPECT_GT(halfway, full / 4);
  EXPECT_LT(halfway, full * 3 / 4);
  EXPECT_LT(none, 5);
}

TEST(Volumes, FogSphereTintsInProportionToThePathInside) {
  // A blue fog sphere of radius 2 m centred 2.5 m above the floor, seen
  // from 10 m above it.
  auto plain = build("");
  auto fog = build("local_fog /World/Fog 0 0 2.5 2 color=0,0,1 density=0.4 edgeFade=0 noiseStrength=0\n");
  EXPECT_EQ(fog->scene.skipped.count("local_fog"), 0u);
  Image ref = draw(plain->scene, topDown(), "fog_none");
  Image im = draw(fog->scene, topDown(), "fog_sphere");
  ASSERT_EQ(im.width, kSide);
  // The fraction of the floor's red hidden by the fog: 1 - exp(-density x
  // the chord of the eye -> floor ray through the sphere).
  auto hidden = [&](double x) {
    auto p = pixelOf(x, 0);
    return 1 - linear(at(im, p).r) / linear(at(ref, p).r);
  };
  auto expected = [](double x) {
    Eigen::Vector3d eye(0, 0, kHeight), d = (Eigen::Vector3d(x, 0, 0) - eye).normalized();
    double off = (Eigen::Vector3d(0, 0, 2.5) - eye).cross(d).norm();
    return off >= 2 ? 0.0 : 1 - std::exp(-0.4 * 2 * std::sqrt(4 - off * off));
  };
  EXPECT_NEAR(hidden(0), expected(0), 0.05);      // 4 m inside: 0.80
  EXPECT_NEAR(hidden(2.5), expected(2.5), 0.05);  // 1.7 m inside: 0.49
  EXPECT_GT(hidden(0), hidden(2.5) + 0.2);
  EXPECT_NEAR(hidden(3.5), 0, 0.01);              // the ray passes beside the sphere
  Rgb outside = at(im, pixelOf(3.5, 0)), outsideRef = at(ref, pixelOf(3.5, 0));
  EXPECT_NEAR(outside.b, outsideRef.b, 1);
}

TEST(Volumes, FogSphereTintsTheSkyBehindIt) {
  // Seen from the side against the procedural sky, with no surface behind.
  const std::string body = "local_fog /World/Fog 10 0 3 2 color=1,0,0 density=1 edgeFade=0\n";
  auto b = build(body, "backgroundMode=rayrai_sky");
  auto ref = build("", "backgroundMode=rayrai_sky");
  View v = topDown();
  v.camera.world.position = Eigen::Vector3d(0, 0, 3);
  v.camera.world.orientation = Eigen::Quaterniond::Identity();  // along +x
  Image im = draw(b->scene, v, "fog_sky"), sky = draw(ref->scene, v, "fog_sky_ref");
  ASSERT_EQ(im.width, kSide);
  std::pair<int, int> centre{kSide / 2, kSide / 2 - 15};  // above the horizon, through the sphere
  EXPECT_GT(redness(at(im, centre)), redness(at(sky, centre)) + 80);
  std::pair<int, int> beside{10, 10};
  EXPECT_EQ(redness(at(im, beside)), redness(at(sky, beside)));
}

TEST(Volumes, HeightFogIsThickerNearItsBase) {
  // A white wall 10 m ahead seen level from 3 m up: its foot and top are as
  // far, but the fog is denser near the ground.
  const std::string wall =
      "object /World/Wall box 10.5 0 3 1 0 0 0 1 40 6 0.5 1 1 default white false true false - static true 1 "
      "18446744073709551615\n";
  auto fog = build(wall, "fogColor=0,0,1 heightFogEnabled=true heightFogDensity=0.3 heightFogBaseHeight=0 "
                         "heightFogFalloff=1");
  auto clear = build(wall, "fogColor=0,0,1 heightFogEnabled=false heightFogDensity=0.3");
  View v = topDown();
  v.camera.world.position = Eigen::Vector3d(0, 0, 3);
  v.camera.world.orientation = Eigen::Quaterniond::Identity();
  Image im = draw(fog->scene, v, "height_fog"), ref = draw(clear->scene, v, "height_fog_off");
  ASSERT_EQ(im.width, kSide);
  double f = kSide / 2.0 / std::tan(M_PI / 6);  // px per unit of z/x
  std::pair<int, int> low{kSide / 2, int(kSide / 2 + f * 2.5 / 10)}, high{kSide / 2, int(kSide / 2 - f * 2.5 / 10)};
  auto blueness = [](Rgb c) { return c.b - c.r; };
  EXPECT_GT(blueness(at(im, low)), blueness(at(im, high)) + 20);  // z = 0.5 against z = 5.5
  EXPECT_GT(blueness(at(im, high)), 0);
  EXPECT_NEAR(blueness(at(ref, low)), 0, 2);
  EXPECT_NEAR(blueness(at(ref, high)), 0, 2);
}

TEST(Volumes, IrradianceVolumeBrightensWhatIsInsideOnly) {
  auto plain = build("");
  auto lit = build("irradiance_volume /World/Green 0 0 0 1 0 0 0 1 1 1 halfExtents=1,1,1 color=0,1,0,1 "
                   "strength=1 edgeFade=0 normalBias=0.02\n");
  EXPECT_EQ(lit->scene.skipped.count("irradiance_volume"), 0u);
  Image ref = draw(plain->scene, topDown(), "irradiance_none");
  Image im = draw(lit->scene, topDown(), "irradiance");
  ASSERT_EQ(im.width, kSide);
  Rgb inside = at(im, pixelOf(0, 0)), insideRef = at(ref, pixelOf(0, 0));
  EXPECT_GT(inside.g, insideRef.g + 40);
  EXPECT_NEAR(inside.r, insideRef.r, 2);
  Rgb outside = at(im, pixelOf(1.5, 0)), outsideRef = at(ref, pixelOf(1.5, 0));
  EXPECT_NEAR(outside.g, outsideRef.g, 1);
}

TEST(Volumes, IrradianceVolumeFadesOverEdgeFadeMetres) {
  auto lit = build("irradiance_volume /World/Green 0 0 0 1 0 0 0 1 1 1 halfExtents=2,2,1 color=0,1,0,1 "
                   "strength=1 edgeFade=1 normalBias=0\n");
  auto plain = build("");
  Image im = draw(lit->scene, topDown(), "irradiance_fade"), ref = draw(plain->scene, topDown(), "irradiance_ref");
  ASSERT_EQ(im.width, kSide);
  int gain0 = at(im, pixelOf(0, 0)).g - at(ref, pixelOf(0, 0)).g;
  int gainEdge = at(im, pixelOf(1.75, 0)).g - at(ref, pixelOf(1.75, 0)).g;  // 0.25 m from the face
  EXPECT_GT(gain0, 40);
  EXPECT_GT(gainEdge, 2);
  EXPECT_LT(gainEdge, gain0 * 0.6);
}

TEST(Volumes, DecalsNeverPaintTheBackground) {
  // A decal box floating in front of the sky, nothing inside it.
  auto with = build(decal("") + "projected_decal /World/Sky 10 0 3 1 0 0 0 1 1 1 halfExtents=2,2,2 color=1,0,0,1\n",
                    "backgroundMode=rayrai_sky");
  auto without = build(decal(""), "backgroundMode=rayrai_sky");
  View v = topDown();
  v.camera.world.position = Eigen::Vector3d(0, 0, 3);
  v.camera.world.orientation = Eigen::Quaterniond::Identity();
  Image a = draw(with->scene, v, "decal_sky"), b = draw(without->scene, v, "decal_sky_ref");
  ASSERT_EQ(a.width, kSide);
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  EXPECT_EQ(a.rgba, b.rgba);
}

TEST(Volumes, WeatherFogAddsToTheEnvironmentsAndNoneIsSkipped) {
  auto b = build("weather true preset=fog fogDensity=0.05\n"
                 "local_fog /World/Fog 0 0 2.5 2\n"
                 "irradiance_volume /World/Light 0 0 0 1 0 0 0 1 1 1\n" +
                     decal(""),
                 "fogColor=0,0,1");
  EXPECT_NEAR(b->scene.environment.fogDensity, 0.05, 1e-6);
  auto off = build("weather false preset=fog fogDensity=0.05\n");
  EXPECT_EQ(off->scene.environment.fogDensity, 0);
  EXPECT_TRUE(b->scene.skipped.empty());
  ASSERT_EQ(b->scene.fogs.size(), 1u);
  // Colors as the shaders take them: linear.
  EXPECT_NEAR(b->scene.fogs[0].color.x(), 1, 1e-6);
  EXPECT_EQ(b->scene.irradianceVolumes.size(), 1u);
}
