// The JSON form: lossless round trip (also after a re-serialisation like
// `jq .`), types from the schema, and errors with JSON pointers.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "core/json.hpp"
#include "test_util.hpp"

using namespace rscene;
namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

namespace {

// fmt(x) == from_json(to_json(x)), directly and after nlohmann re-dumps the
// JSON (it prints numbers shortest-round-trip like jq 1.6).
void expectRoundTrip(const std::string& text, const std::string& what) {
  SCOPED_TRACE(what);
  LoadResult loaded = parse(text);
  if (!loaded.ok()) return;
  std::string canonical = canonicalText(loaded.document);
  for (bool pretty : {false, true}) {
    std::string j = toJson(loaded.document, JsonStyle{pretty});
    JsonLoadResult back = fromJson(j);
    ASSERT_TRUE(back.ok()) << back.diagnostics[0].message << "\n" << j;
    EXPECT_EQ(canonicalText(back.document), canonical) << j;
    std::string redumped = Json::parse(j).dump(2);
    JsonLoadResult again = fromJson(redumped);
    ASSERT_TRUE(again.ok()) << again.diagnostics[0].message;
    EXPECT_EQ(canonicalText(again.document), canonical) << redumped;
  }
}

std::string firstMessage(const JsonLoadResult& r) { return r.diagnostics.empty() ? "" : r.diagnostics[0].message; }

std::string sceneJson(const std::string& records) {
  return R"({"format":"rscene","version":1,"records":[{"tag":"raisim_engine_scene","fields":{"version":1}})" +
         records + "]}";
}

}  // namespace

TEST(Json, EveryFixtureRoundTrips) {
  std::vector<fs::path> files = test::scenesIn(fs::path(RSCENE_TEST_DATA));
  for (const fs::path& f : test::scenesIn(fs::path(RSCENE_TEST_DATA) / ".." / ".." / "examples")) files.push_back(f);
  for (const fs::path& f : test::scenesIn(fs::path(RSCENE_SHARED_DIR) / "corpus")) files.push_back(f);
  ASSERT_FALSE(files.empty());
  for (const fs::path& f : files) expectRoundTrip(test::readAll(f), f.string());
}

TEST(Json, FieldsCarrySchemaNamesAndTypes) {
  LoadResult r = parse(
      "raisim_engine_scene 1\n"
      "# the box\n"
      "object /World/Box box 0 0 0.5 1 0 0 0 1 1 1 0.5 1 2.5 default mat false true false - dynamic true 1 "
      "18446744073709551615 id=box_a futureKey=%20x semanticClass=\n"
      "terrain_region /World/T 2 2 1 1 0 0 0 heights=0.1,-0,0.3,29.999999999999996 vertexColors=1,1,1,1;0,0,0,1\n");
  ASSERT_TRUE(r.ok());
  Json j = Json::parse(toJson(r.document));
  EXPECT_EQ(j["format"], "rscene");
  EXPECT_EQ(j["version"], 1);
  const Json& box = j["records"][1];
  EXPECT_EQ(box["tag"], "object");
  EXPECT_EQ(box["line"], 3);
  EXPECT_EQ(box["comments"], Json::array({"# the box"}));
  EXPECT_EQ(box["fields"]["position"], Json::array({0, 0, 0.5}));
  EXPECT_EQ(box["fields"]["mass"], 2.5);
  EXPECT_EQ(box["fields"]["visible"], true);
  EXPECT_EQ(box["fields"]["meshPath"], "");
  EXPECT_EQ(box["fields"]["collisionMask"], "18446744073709551615");  // uint64 as a string
  EXPECT_EQ(box["fields"]["futureKey"], " x");
  EXPECT_EQ(box["unknownKeys"], Json::array({"futureKey"}));
  const Json& terrain = j["records"][2];
  EXPECT_EQ(terrain["fields"]["heights"][1], "-0");  // jq 1.6 would lose the sign of -0
  EXPECT_EQ(terrain["fields"]["heights"][3].get<double>(), 29.999999999999996);
  EXPECT_EQ(terrain["fields"]["vertexColors"], Json::parse("[[1,1,1,1],[0,0,0,1]]"));
  EXPECT_EQ(terrain["fields"]["center"], Json::array({0, 0, 0}));
}

TEST(Json, OlderObjectLayoutIsMarked) {
  LoadResult r = parse("raisim_engine_scene 1\nobject /World/B box 0 0 0 1 0 0 0 1 1 1 0.5 1 2 default m true false\n");
  ASSERT_TRUE(r.ok());
  Json j = Json::parse(toJson(r.document));
  EXPECT_EQ(j["records"][1]["positionalCount"], 19);
  EXPECT_EQ(j["records"][1]["fields"]["fixed"], false);
  expectRoundTrip(canonicalText(r.document), "19 positionals");
}

TEST(Json, RecordsAnObjectCannotHoldKeepTheirTokens) {
  LoadResult r = parse(
      "raisim_engine_scene 1\n"
      "time_step 0.01 note=a note=b\n"
      "future_thing a k=v b\n");
  ASSERT_TRUE(r.ok());
  Json j = Json::parse(toJson(r.document));
  EXPECT_EQ(j["records"][1]["tokens"], Json::parse(R"(["0.01","note=a","note=b"])"));
  EXPECT_EQ(j["records"][2]["unknownTag"], true);
  EXPECT_EQ(j["records"][2]["tokens"], Json::parse(R"(["a","k=v","b"])"));
  expectRoundTrip(canonicalText(r.document), "tokens");
}

// Every kind, every version, values that do not parse as their type, and
// the spellings the canonical writer keeps apart: random lines must all
// survive the round trip.
TEST(Json, TrickyValuesSurvive) {
  const char* pool[] = {"0", "-0", "-0.0", "1.5", "0.10", "1e-07", "1E5", "1e400", "nan", "abc", "-", "%2D",
                        "%25", "%FF", "%3B", "a%20b", "1,2,3", "1;2;3", "1,2;3,4", "1,,2", ";", ",", "007", "+5",
                        "9007199254740993", "18446744073709551615", "-12", "TRUE", "yes", "1.", ".5", "%2C",
                        "x;-;y", "-;", "29.999999999999996", "1,-0,2", "%C3%A9", "\xC3\xA9", "%0A", "1e+22"};
  const std::size_t n = sizeof(pool) / sizeof(pool[0]);
  std::mt19937 rng(7);
  for (int version = 1; version <= 2; ++version) {
    for (const KindDef& k : Schema::get().kinds()) {
      if (k.tag == "raisim_engine_scene") continue;
      for (int trial = 0; trial < 12; ++trial) {
        std::string text = "raisim_engine_scene " + std::to_string(version) + "\n" + k.tag;
        const Layout& layout = k.layouts[rng() % k.layouts.size()];
        for (std::size_t t = 0; t < layout.tokenCount(); ++t) text += std::string(" ") + pool[rng() % n];
        for (int key = 0; key < 4 && !k.keys.empty(); ++key) {
          const FieldDef& f = k.keys[rng() % k.keys.size()];
          if (text.find(" " + f.name + "=") != std::string::npos) continue;
          text += " " + f.name + "=" + (rng() % 8 == 0 ? "" : pool[rng() % n]);
        }
        text += std::string(" zzFuture=") + (rng() % 3 == 0 ? "" : pool[rng() % n]) + "\n";
        expectRoundTrip(text, text);
      }
    }
  }
}

TEST(Json, SchemaMismatchNamesThePointer) {
  JsonLoadResult r = fromJson(sceneJson(R"(,{"tag":"time_step","fields":{"dt":true}})"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics[0].code, kJsonSchema);
  EXPECT_EQ(firstMessage(r), "/records/1/fields/dt: expected number, got a boolean");

  r = fromJson(sceneJson(R"(,{"tag":"gravity","fields":{"gravity":[0,0]}})"));
  EXPECT_EQ(firstMessage(r), "/records/1/fields/gravity: expected an array of 3 numbers, got an array");

  r = fromJson(sceneJson(R"(,{"tag":"time_step","fields":{"dt":1,"colour":2}})"));
  EXPECT_EQ(firstMessage(r),
            "/records/1/fields/colour: unknown field 'colour' for time_step (list it in 'unknownKeys' to keep it)");

  r = fromJson(sceneJson(R"(,{"tag":"nope","fields":{}})"));
  EXPECT_EQ(firstMessage(r), "/records/1/tag: unknown record kind 'nope'; unknown records keep their text in 'tokens'");

  r = fromJson(sceneJson(R"(,{"tag":"object","fields":{"path":"/World/A"}})"));
  EXPECT_EQ(firstMessage(r), "/records/1/fields: missing positional field 'primitive'");

  r = fromJson(sceneJson(R"(,{"tag":"time_step","tokens":["a b"]})"));
  EXPECT_EQ(firstMessage(r), "/records/1/tokens/0: white space in token (encode it as %20 or %09)");

  r = fromJson(R"({"format":"rscene","version":2,"records":[{"tag":"raisim_engine_scene","fields":{"version":1}}]})");
  EXPECT_EQ(firstMessage(r), "/version: expected 1, the header's version");

  r = fromJson(R"({"format":"xml","records":[]})");
  EXPECT_EQ(firstMessage(r), "/format: expected \"rscene\"");
}

TEST(Json, ErrorsCarryLineAndColumn) {
  JsonLoadResult r = fromJson("{\n  \"format\": \"rscene\",\n  \"version\": 1,\n  \"records\": [\n"
                              "    {\"tag\": \"raisim_engine_scene\", \"fields\": {\"version\": 1}},\n"
                              "    {\"tag\": \"time_step\",\n     \"fields\": {\"dt\": \"x\", \"bad\": 1}}\n  ]\n}\n");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics[0].line, 7u);
  EXPECT_EQ(r.diagnostics[0].column, 28u);  // the "bad" key

  r = fromJson("{\"format\": \"rscene\",\n \"version\": 1,, }");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics[0].code, kJsonSyntax);
  EXPECT_EQ(r.diagnostics[0].line, 2u);
  EXPECT_EQ(r.diagnostics[0].message.rfind("invalid JSON: ", 0), 0u) << r.diagnostics[0].message;

  r = fromJson("");
  EXPECT_EQ(r.diagnostics.at(0).code, kJsonSyntax);
}

TEST(Json, DuplicateMembersAreRefused) {
  JsonLoadResult r = fromJson(sceneJson(R"(,{"tag":"time_step","fields":{"dt":1,"dt":2}})"));
  EXPECT_EQ(firstMessage(r), "/records/1/fields/dt: duplicate member 'dt'");
}

TEST(Json, HandWrittenValuesAreAccepted) {
  JsonLoadResult r = fromJson(sceneJson(
      R"(,{"tag":"object","fields":{"path":"/World/A b","primitive":"box","position":[0,0,1],"orientation":[1,0,0,0],)"
      R"("scale":[1,1,1],"radius":0.5,"height":1,"mass":2,"contactMaterial":"default","material":"m",)"
      R"("visualOnly":false,"visible":true,"locked":false,"meshPath":"","bodyMode":"dynamic","collidable":true,)"
      R"("collisionGroup":1,"collisionMask":"18446744073709551615","id":"a","castShadow":true}})"));
  ASSERT_TRUE(r.ok()) << firstMessage(r);
  EXPECT_EQ(canonicalText(r.document),
            "raisim_engine_scene 1\n"
            "object /World/A%20b box 0 0 1 1 0 0 0 1 1 1 0.5 1 2 default m false true false - dynamic true 1 "
            "18446744073709551615 id=a castShadow=true\n");
}

TEST(Json, SchemaIsGeneratedFromTheTable) {
  Json s = Json::parse(jsonSchema());
  EXPECT_EQ(s["$schema"], "https://json-schema.org/draft/2020-12/schema");
  for (const KindDef& k : Schema::get().kinds()) {
    ASSERT_TRUE(s["$defs"].contains("fields_" + k.tag)) << k.tag;
    for (const FieldDef& f : k.keys) EXPECT_TRUE(s["$defs"]["fields_" + k.tag]["properties"].contains(f.name));
  }
  EXPECT_EQ(s["$defs"]["fields_object"]["properties"]["collisionMask"]["$ref"], "#/$defs/uint64");
}

// 100 k nested containers (600 KB) once took 56 s: every key rebuilt a
// JSON pointer as long as the nesting.  Deeper than a scene can be is now
// refused where it starts, in time linear in the input.
TEST(Json, DeepNestingIsRefusedAtOnce) {
  const int n = 100000;
  std::string deep;
  for (int i = 0; i < n; ++i) deep += "{\"a\":";
  deep += "1";
  deep.append(n, '}');
  JsonLoadResult r = fromJson(sceneJson(",{\"tag\":\"object\",\"x\":" + deep + "}"));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.diagnostics[0].code, kJsonSchema);
  EXPECT_NE(firstMessage(r).find("nesting deeper than 32 levels"), std::string::npos) << firstMessage(r);

  r = fromJson("{\"zz\":" + deep + "}");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(firstMessage(r).find("nesting deeper than 32 levels"), std::string::npos) << firstMessage(r);
}
