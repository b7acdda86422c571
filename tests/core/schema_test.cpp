#include <gtest/gtest.h>

#include "core/schema.hpp"
#include "core/text.hpp"

using namespace rscene;

TEST(Schema, CoversAllThirtyNineTagsOfTheFormat) {
  const char* tags[] = {"raisim_engine_scene", "time_step", "gravity", "solver", "snapping", "asset_root",
                        "scene_graph", "prefab_override", "editor_ux", "render_bake", "environment", "weather",
                        "rayrai_render", "material", "contact_material", "terrain_texture", "asset",
                        "articulated_resource", "group", "terrain_region", "terrain_splat_layer",
                        "terrain_foliage_layer", "light", "camera", "object", "compound", "compound_child",
                        "deformable", "granular", "articulated", "articulated_ik", "sensor", "wire",
                        "reflection_probe", "local_fog", "projected_decal", "irradiance_volume", "point_cloud",
                        "instanced_visual"};
  EXPECT_EQ(Schema::get().kinds().size(), 39u);
  for (const char* t : tags) EXPECT_NE(Schema::get().kind(t), nullptr) << t;
  EXPECT_EQ(Schema::get().kind("objcet"), nullptr);
}

TEST(Schema, PositionalLayoutsMatchTheFormatDescription) {
  const Schema& s = Schema::get();
  EXPECT_EQ(s.kind("object")->layouts.size(), 3u);
  EXPECT_NE(s.kind("object")->layoutFor(25), nullptr);
  EXPECT_NE(s.kind("object")->layoutFor(19), nullptr);
  EXPECT_NE(s.kind("object")->layoutFor(17), nullptr);
  EXPECT_EQ(s.kind("object")->layoutFor(18), nullptr);
  EXPECT_NE(s.kind("camera")->layoutFor(15), nullptr);
  EXPECT_NE(s.kind("material")->layoutFor(18), nullptr);
  EXPECT_NE(s.kind("environment")->layoutFor(11), nullptr);
  EXPECT_NE(s.kind("snapping")->layoutFor(12), nullptr);
  EXPECT_NE(s.kind("solver")->layoutFor(4), nullptr);
  EXPECT_NE(s.kind("contact_material")->layoutFor(9), nullptr);
  EXPECT_NE(s.kind("terrain_region")->layoutFor(8), nullptr);
  EXPECT_NE(s.kind("articulated_ik")->layoutFor(3), nullptr);
  EXPECT_NE(s.kind("wire")->layoutFor(5), nullptr);
  EXPECT_NE(s.kind("scene_graph")->layoutFor(0), nullptr);
  // The 25-field object layout puts the uint64 group and mask last.
  const KindDef* o = s.kind("object");
  EXPECT_EQ(o->positionalToken(25, 23)->type, ValueType::Group);
  EXPECT_EQ(o->positionalToken(25, 24)->name, "collisionMask");
  EXPECT_EQ(o->positionalToken(25, 5)->name, "orientation");
}

TEST(Schema, KeysAreTypedAndEnumsResolveAliasesCaseInsensitively) {
  const KindDef* o = Schema::get().kind("object");
  ASSERT_NE(o->key("collisionMode"), nullptr);
  EXPECT_EQ(o->key("collisionMode")->type, ValueType::Name);
  const EnumDef* mode = o->key("collisionMode")->enumDef;
  ASSERT_NE(mode, nullptr);
  EXPECT_EQ(mode->canonical("TriMesh"), "original_mesh");
  EXPECT_EQ(mode->canonical("coacd"), "convexify");
  EXPECT_FALSE(mode->canonical("bogus").has_value());
  EXPECT_EQ(Schema::get().enumDef("body_mode")->canonical("movable"), "dynamic");
  EXPECT_EQ(Schema::get().enumDef("primitive")->canonical("CUBE"), "box");
  EXPECT_TRUE(Schema::get().enumDef("sensor_kind")->open);
  EXPECT_FALSE(Schema::get().enumDef("primitive")->open);
}

TEST(Schema, EveryDefaultParsesAsItsType) {
  for (const KindDef& k : Schema::get().kinds()) {
    auto check = [&](const FieldDef& f) {
      if (!f.defaultValue) return;
      std::vector<double> nums;
      switch (f.type) {
        case ValueType::Number: EXPECT_TRUE(parseNumber(*f.defaultValue)) << k.tag << "." << f.name; break;
        case ValueType::Integer: EXPECT_TRUE(parseInteger(*f.defaultValue)) << k.tag << "." << f.name; break;
        case ValueType::Flag: EXPECT_TRUE(parseFlag(*f.defaultValue)) << k.tag << "." << f.name; break;
        case ValueType::Name:
          if (f.enumDef) {
            EXPECT_TRUE(f.enumDef->canonical(*f.defaultValue)) << k.tag << "." << f.name;
          }
          break;
        default:
          if (isNumericList(f.type)) {
            EXPECT_TRUE(parseNumberList(*f.defaultValue, nums)) << k.tag << "." << f.name;
            if (componentCount(f.type) && f.type != ValueType::Color) {
              EXPECT_EQ(nums.size(), static_cast<std::size_t>(componentCount(f.type))) << k.tag << "." << f.name;
            }
          }
      }
    };
    for (const Layout& l : k.layouts)
      for (const FieldDef& f : l.fields) check(f);
    for (const FieldDef& f : k.keys) check(f);
  }
}

TEST(Schema, ChildrenNameAParentKindThatExists) {
  int children = 0;
  for (const KindDef& k : Schema::get().kinds()) {
    if (k.role != Role::Child) continue;
    ++children;
    const KindDef* parent = Schema::get().kind(k.parentTag);
    ASSERT_NE(parent, nullptr) << k.tag;
    EXPECT_EQ(parent->rank, k.rank) << k.tag;
  }
  EXPECT_EQ(children, 4);
}
