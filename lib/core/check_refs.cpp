// RS3003..RS3017: identity (paths, ids), references between records,
// child records and repeated singletons.
#include <algorithm>

#include "core/codes.hpp"
#include "core/assets.hpp"
#include "core/check_context.hpp"
#include "core/suggest.hpp"
#include "core/text.hpp"

namespace rscene::checks {
namespace {

// Names that exist in every scene (compat-notes.md, "Identity and defaults").
constexpr std::string_view kDefaultMaterial = "engine_default";
constexpr std::string_view kDefaultContact = "default";
constexpr std::int64_t kDefaultTextureSlots = 2;  // terrain_grass, terrain_rock

bool isUnderWorld(std::string_view path) { return path == "/World" || path.rfind("/World/", 0) == 0; }

std::string lineRef(const Document& doc, std::uint32_t index) {
  return "line " + std::to_string(doc.records[index].line);
}

// The names a reference of kind `what` (material, contact, resource, or a
// node: `node`, `body`, `terrain`, `node:<tag>` for a child's parent) can
// name: sorted names for the maps, file order (id, then path) for nodes.
std::vector<std::string_view> referenceNames(Context& ctx, const std::string& what) {
  auto& ix = ctx.index;
  std::vector<std::string_view> names;
  auto keysOf = [&](const auto& map, std::string_view builtIn) {
    names.push_back(builtIn);
    for (const auto& entry : map)
      if (!entry.first.empty()) names.push_back(entry.first);
    std::sort(names.begin() + 1, names.end());
  };
  if (what == "material") {
    keysOf(ix.materials, kDefaultMaterial);
  } else if (what == "contact") {
    keysOf(ix.contacts, kDefaultContact);
  } else if (what == "resource") {
    keysOf(ix.resources, {});
  } else {
    std::string_view tag = what == "terrain"                ? "terrain_region"
                           : what.rfind("node:", 0) == 0 ? std::string_view(what).substr(5)
                                                         : "";
    const Document& doc = ctx.doc;
    for (std::size_t i = 0; i < doc.records.size(); ++i) {
      const KindDef* k = doc.records[i].kind;
      if (!k || !k->isNode() || (!tag.empty() && k->tag != tag)) continue;
      if (!ix.idOf[i].empty()) names.push_back(ix.idOf[i]);
      else if (!k->idPrefix.empty()) names.push_back(ix.owned.emplace_back(k->idPrefix + std::string(ix.pathOf[i])));
      names.push_back(ix.pathOf[i]);
    }
  }
  names.erase(std::remove(names.begin(), names.end(), std::string_view()), names.end());
  return names;
}

// How far a name may be from the one meant: a third of what is its own,
// not counting the `/World/` (and `folder_/World/` ...) every node path and
// default id starts with, or `/World/Prop` would take `/World/Cart`.
std::size_t typoLimit(std::string_view name) {
  std::size_t shared = 0;
  constexpr std::string_view kWorld = "/World/";
  for (const KindDef& k : Schema::get().kinds()) {
    std::string_view rest = name;
    if (!k.idPrefix.empty() && rest.rfind(k.idPrefix, 0) == 0) rest.remove_prefix(k.idPrefix.size());
    if (rest.rfind(kWorld, 0) == 0) shared = std::max(shared, name.size() - rest.size() + kWorld.size());
  }
  return std::max<std::size_t>(1, (name.size() - shared + 1) / 3);
}

// The name a reference to nothing most likely meant: the closest one of the
// same kind (`mat_bx` -> `mat_box`, `folder_prop` -> `folder_props`), or
// else the one node path that ends in it (`Props` -> `/World/Props`).
// Empty when nothing is close, or when the comparison budget is spent.
std::string suggestReference(Context& ctx, const std::string& what, std::string_view name) {
  auto& ix = ctx.index;
  std::string key = what + '\n' + std::string(name);
  if (auto it = ix.refSuggestions.find(key); it != ix.refSuggestions.end()) return it->second;
  auto [entry, fresh] = ix.refCandidates.try_emplace(what);
  if (fresh) entry->second = referenceNames(ctx, what);
  const std::vector<std::string_view>& names = entry->second;
  std::string best;
  if (names.size() <= ix.refBudget) {
    ix.refBudget -= names.size();
    best = closestName(name, names, typoLimit(name));
    for (std::string_view n : names) {
      if (!best.empty()) break;
      if (n.size() > name.size() && n[0] == '/' && n.substr(n.size() - name.size()) == name && n[n.size() - name.size() - 1] == '/')
        best = n;
    }
  }
  ix.refSuggestions.emplace(std::move(key), best);
  return best;
}

void resolve(Context& ctx, std::size_t i, const FieldDef& def, const Field& f, std::string& scratch) {
  const Document& doc = ctx.doc;
  const Record& r = doc.records[i];
  const auto& ix = ctx.index;
  std::string_view raw = doc.text(f.value);
  if (def.type == ValueType::Integer && def.arg == "texslot") {
    auto slot = parseInteger(raw);
    if (!slot || (*slot >= 0 && *slot < kDefaultTextureSlots)) return;
    if (std::find(ix.textureSlots.begin(), ix.textureSlots.end(), *slot) != ix.textureSlots.end()) return;
    ctx.report(rs::RS3011, r, f.value, def.name, "terrain texture slot " + std::to_string(*slot) + " does not exist",
               "slots 0 and 1 exist by default; add a terrain_texture record for others");
    return;
  }
  if (def.type != ValueType::Ref) return;
  std::string_view name = Context::decode(raw, scratch);
  if (name.empty()) return;  // no reference
  const std::string& what = def.arg;
  // Names the closest existing target instead of the general hint when
  // there is one; `targets` is the kind of name (see referenceNames).
  auto missing = [&](std::string_view code, std::string_view noun, std::string hint = {},
                     const std::string& targets = {}) {
    std::string best = suggestReference(ctx, targets.empty() ? what : targets, name);
    if (!best.empty()) hint = "did you mean `" + best + "`?";
    ctx.report(code, r, f.value, def.name, std::string(noun) + " '" + std::string(name) + "' does not exist",
               std::move(hint));
  };
  if (what == "material") {
    if (name != kDefaultMaterial && !ix.materials.count(name))
      missing(rs::RS3008, "material", "engine_default always exists; other names need a material record");
  } else if (what == "contact") {
    if (name != kDefaultContact && !ix.contacts.count(name))
      missing(rs::RS3009, "contact material",
              "the default contact properties apply; name it in a contact_material record to set its own");
  } else if (what == "resource") {
    if (!ix.resources.count(name)) missing(rs::RS3010, "articulated resource");
  } else if (what == "terrain") {
    if (!ctx.terrain(name)) missing(rs::RS3013, "terrain");
  } else if (what == "body") {
    if (!ctx.node(name)) missing(rs::RS3012, "body", "name a node by its id or path");
  } else if (what == "node") {
    const Record* target = ctx.node(name);
    bool parentField = def.name == "parentGroupId" || def.name == "parentId";
    if (parentField) {
      if (!target) {
        missing(rs::RS3006, "parent", "name a group by its id or path");
        return;
      }
      auto targetIndex = static_cast<std::uint32_t>(target - doc.records.data());
      ctx.index.parentOf[i] = targetIndex;
      if (target->kind->tag != "group" && ix.inheritedTransforms) {
        const std::string& k = target->kind->tag;
        std::string msg = "parent '" + std::string(name) + "' is " + (k.find_first_of("aeiou") == 0 ? "an " : "a ") + k +
                          ", not a group";
        // A camera on a body rides on it (render and sim mount it there):
        // meant, documented, no mistake to warn of.
        bool cameraOnBody = r.kind->tag == "camera" && (k == "object" || k == "compound" || k == "articulated");
        if (ctx.raisim())
          ctx.report(rs::RS6004, r, f.value, def.name, msg + "; RaiSim refuses inherited transforms",
                     "parent the node to a group, or set scene_graph inheritedTransforms=false");
        else if (!cameraOnBody)
          ctx.report(rs::RS3007, r, f.value, def.name, msg + "; the node inherits its transform",
                     "parent the node to a group if it should stay in the world frame");
      }
      return;
    }
    // A child names its parent record kind (compound_child -> compound ...).
    const std::string& want = r.kind->parentTag;
    if (!target || (!want.empty() && target->kind->tag != want))
      missing(rs::RS3014, want.empty() ? "node" : want, {}, want.empty() ? "node" : "node:" + want);
  }
}

}  // namespace

void buildIndex(Context& ctx) {
  const Document& doc = ctx.doc;
  auto& ix = ctx.index;
  ix.parentOf.assign(doc.records.size(), Context::kNoRecord);
  ix.pathOf.assign(doc.records.size(), {});
  ix.idOf.assign(doc.records.size(), {});
  ix.firstWithPath.assign(doc.records.size(), Context::kNoRecord);
  ix.firstWithId.assign(doc.records.size(), Context::kNoRecord);
  ix.lastOfKind.assign(Schema::get().kinds().size(), Context::kNoRecord);
  std::size_t nodes = 0;
  for (const Record& r : doc.records) nodes += r.kind && r.kind->isNode();
  ix.nodeByPath.reserve(nodes);
  ix.nodeById.reserve(nodes);
  // Most text needs no decoding: keep a view of the document's buffer.
  auto keep = [&](std::string_view raw) -> std::string_view {
    if (raw.find('%') == std::string_view::npos && raw != "-") return raw;
    return ix.owned.emplace_back(percentDecode(raw));
  };
  auto own = [&](std::string s) -> std::string_view { return ix.owned.emplace_back(std::move(s)); };
  ix.assetRoot = assetRootOf(doc);
  for (std::size_t i = 0; i < doc.records.size(); ++i) {
    const Record& r = doc.records[i];
    if (!r.kind) continue;
    auto index = static_cast<std::uint32_t>(i);
    const std::string& tag = r.kind->tag;
    if (r.kind->isNode()) {
      std::string_view path = keep(doc.positionalText(r, 0));
      ix.pathOf[i] = path;
      ix.firstWithPath[i] = ix.nodeByPath.emplace(index);
      if (const Field* id = doc.find(r, "id")) {
        std::string_view v = keep(doc.text(id->value));
        if (!v.empty()) {
          ix.idOf[i] = v;
          ix.firstWithId[i] = ix.nodeById.emplace(index);
        }
      }
    } else if (tag == "material") {
      ix.materials.emplace(own(nodeId(doc, r)), index);
      ix.materials.emplace(own(ctx.text(r, "name")), index);
    } else if (tag == "contact_material") {
      for (std::string_view k : {"materialA", "materialB", "id"}) ix.contacts.emplace(own(ctx.text(r, k)), true);
    } else if (tag == "articulated_resource") {
      ix.resources.emplace(own(ctx.text(r, "id")), index);
      ix.resources.emplace(own(ctx.text(r, "name")), index);
    } else if (tag == "terrain_texture") {
      if (auto slot = ctx.integer(r, "slot")) ix.textureSlots.push_back(*slot);
    } else if (tag == "scene_graph") {
      if (auto inherited = ctx.flag(r, "inheritedTransforms")) ix.inheritedTransforms = *inherited;
      else if (!ctx.get(r, "inheritedTransforms")) ix.inheritedTransforms = true;
    }
  }
}

void checkRefs(Context& ctx, std::size_t i) {
  const Document& doc = ctx.doc;
  const Record& r = doc.records[i];
  const KindDef& kind = *r.kind;
  auto& ix = ctx.index;
  auto index = static_cast<std::uint32_t>(i);

  if (kind.isNode()) {
    std::string_view path = ix.pathOf[i];
    Span at = doc.positional(r, 0)->value;
    if (!isUnderWorld(path))
      ctx.report(rs::RS3005, r, at, "path", "path '" + std::string(path) + "' is not under /World",
                 "node paths start with /World/");
    // buildIndex noted the first node with each path.
    if (std::uint32_t first = ix.firstWithPath[i]; first != Context::kNoRecord && first != index)
      ctx.report(rs::RS3003, r, at, "path", "duplicate path '" + std::string(path) + "'; first used on " + lineRef(doc, first));
    // An id is taken when another node has it as id= or as its default id.
    // Two default ids collide only with a duplicate path (reported above).
    bool explicitId = ctx.hasExplicitId(r);
    const Record* other = nullptr;
    std::string id;
    if (explicitId && ix.firstWithId[i] != Context::kNoRecord) {
      // buildIndex noted the first node with this id= (maybe this one).
      other = &doc.records[ix.firstWithId[i]];
      if (other != &r) id = nodeId(doc, r);
    } else {
      id = explicitId || kind.idPrefix.empty() ? nodeId(doc, r) : kind.idPrefix + std::string(path);
      if (std::uint32_t it = ix.nodeById.find(id); !id.empty() && it != TextIndex::kNone) other = &doc.records[it];
      if (!other && explicitId && id[0] != '/') other = ctx.node(id);  // another node's default id
    }
    if (other && other != &r) {
      const FieldRef idField = ctx.get(r, "id");
      ctx.report(rs::RS3004, r, idField ? idField.first->value : at, "id",
                 std::string(explicitId ? "duplicate id '" : "duplicate default id '") + id + "'; first used on " +
                     lineRef(doc, static_cast<std::uint32_t>(other - doc.records.data())),
                 explicitId ? "" : "set a distinct id= on one of them");
    }
  } else if (kind.tag == "material") {
    std::string id = nodeId(doc, r);
    if (auto it = ix.materials.find(id); it != ix.materials.end() && it->second != index &&
                                         nodeId(doc, doc.records[it->second]) == id)
      ctx.report(rs::RS3004, r, doc.positional(r, 0)->value, "id",
                 "duplicate material id '" + id + "'; first used on " + lineRef(doc, it->second));
  }

  const std::size_t k = Context::kindIndex(kind);
  if (kind.role == Role::Singleton) {
    if (std::uint32_t last = ix.lastOfKind[k]; last != Context::kNoRecord)
      ctx.report(rs::RS3016, r, r.tag, {}, "repeated " + kind.tag + " replaces the one on " + lineRef(doc, last),
                 "remove the earlier record; it is ignored");
  }
  if (kind.role == Role::Child) {
    const KindDef* parent = Schema::get().kind(kind.parentTag);
    if (!parent || ix.lastOfKind[Context::kindIndex(*parent)] == Context::kNoRecord)
      ctx.report(rs::RS3015, r, r.tag, {}, kind.tag + " has no " + kind.parentTag + " record before it",
                 "place it after the " + kind.parentTag + " it belongs to");
  }
  ix.lastOfKind[k] = index;

  std::string scratch;
  forEachValue(ctx, r, [&](const FieldDef& def, const Field& f) {
    if (def.type == ValueType::Ref || def.type == ValueType::Integer) resolve(ctx, i, def, f, scratch);
  });
}

void checkParentCycles(Context& ctx) {
  const auto& parent = ctx.index.parentOf;
  std::vector<std::uint8_t> state(parent.size(), 0);  // 0 new, 1 on the walk, 2 done
  std::vector<std::uint32_t> walk;
  for (std::uint32_t start = 0; start < parent.size(); ++start) {
    walk.clear();
    std::uint32_t n = start;
    while (n != Context::kNoRecord && state[n] == 0) {
      state[n] = 1;
      walk.push_back(n);
      n = parent[n];
    }
    if (n != Context::kNoRecord && state[n] == 1) {
      const Record& r = ctx.doc.records[n];
      FieldRef f = ctx.get(r, r.kind->tag == "group" ? "parentId" : "parentGroupId");
      if (!f) f = ctx.get(r, "parentGroupId");
      ctx.report(rs::RS3017, r, ctx.spanOf(r, f), f.def ? f.def->name : "",
                 "node '" + nodePath(ctx.doc, r) + "' is its own ancestor", "break the cycle of parents");
    }
    for (std::uint32_t w : walk) state[w] = 2;
  }
}

}  // namespace rscene::checks
