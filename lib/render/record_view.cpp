#include "render/record_view.hpp"

#include "core/text.hpp"

namespace rscene::render {

std::string RecordView::raw(std::string_view name) const {
  if (const Field* f = doc_.find(r_, name)) return std::string(doc_.text(f->value));
  if (!r_.kind) return {};
  const Layout* layout = r_.kind->layoutFor(r_.positionalCount);
  if (!layout) return {};
  std::string out;
  bool found = false;
  for (std::size_t i = 0; i < layout->tokens.size(); ++i) {
    const FieldDef& fd = layout->fields[static_cast<std::size_t>(layout->tokens[i].first)];
    if (fd.name != name) continue;
    if (found) out += ',';
    out += doc_.positionalText(r_, static_cast<std::uint32_t>(i));
    found = true;
  }
  return out;
}

bool RecordView::has(std::string_view name) const {
  if (doc_.find(r_, name)) return true;
  if (!r_.kind) return false;
  const Layout* layout = r_.kind->layoutFor(r_.positionalCount);
  if (!layout) return false;
  for (const FieldDef& fd : layout->fields)
    if (fd.name == name) return true;
  return false;
}

std::string RecordView::schemaDefault(std::string_view name) const {
  if (!r_.kind) return {};
  if (const FieldDef* k = r_.kind->key(name)) return k->defaultValue.value_or("");
  for (const Layout& l : r_.kind->layouts)
    for (const FieldDef& fd : l.fields)
      if (fd.name == name) return fd.defaultValue.value_or("");
  return {};
}

std::string RecordView::text(std::string_view name) const { return percentDecode(raw(name)); }

std::string RecordView::name(std::string_view field, std::string_view fallback) const {
  std::string value = text(field);
  if (value.empty()) value = schemaDefault(field);
  if (value.empty()) return std::string(fallback);
  const FieldDef* fd = r_.kind ? r_.kind->key(field) : nullptr;
  if (!fd && r_.kind)
    for (const FieldDef& f : r_.kind->layouts.front().fields)
      if (f.name == field) fd = &f;
  if (fd && fd->enumDef)
    if (auto c = fd->enumDef->canonical(value)) return std::string(*c);
  for (char& c : value) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return value;
}

double RecordView::number(std::string_view name, double fallback) const {
  if (auto v = parseNumber(percentDecode(raw(name)))) return *v;
  if (auto v = parseNumber(schemaDefault(name))) return *v;
  return fallback;
}

bool RecordView::flag(std::string_view name, bool fallback) const {
  if (auto v = parseFlag(percentDecode(raw(name)))) return *v;
  if (auto v = parseFlag(schemaDefault(name))) return *v;
  return fallback;
}

std::vector<double> RecordView::numbers(std::string_view name) const {
  std::vector<double> out;
  if (!parseNumberList(percentDecode(raw(name)), out)) out.clear();
  return out;
}

namespace {
bool listOf(const std::string& text, std::size_t minN, std::size_t maxN, std::vector<double>& out) {
  out.clear();
  return parseNumberList(text, out) && out.size() >= minN && out.size() <= maxN;
}
}  // namespace

Eigen::Vector3d RecordView::vec3(std::string_view name, const Eigen::Vector3d& fallback) const {
  std::vector<double> v;
  if (listOf(percentDecode(raw(name)), 3, 3, v) || listOf(schemaDefault(name), 3, 3, v))
    return {v[0], v[1], v[2]};
  return fallback;
}

Eigen::Vector2d RecordView::vec2(std::string_view name, const Eigen::Vector2d& fallback) const {
  std::vector<double> v;
  if (listOf(percentDecode(raw(name)), 2, 2, v) || listOf(schemaDefault(name), 2, 2, v)) return {v[0], v[1]};
  return fallback;
}

Eigen::Vector4d RecordView::color(std::string_view name, const Eigen::Vector4d& fallback) const {
  std::vector<double> v;
  if (listOf(percentDecode(raw(name)), 3, 4, v) || listOf(schemaDefault(name), 3, 4, v))
    return {v[0], v[1], v[2], v.size() == 4 ? v[3] : 1.0};
  return fallback;
}

Eigen::Quaterniond RecordView::quat(std::string_view name) const {
  std::vector<double> v;
  if (listOf(percentDecode(raw(name)), 4, 4, v)) {
    Eigen::Quaterniond q(v[0], v[1], v[2], v[3]);
    if (q.norm() > 1e-12) return q.normalized();
  }
  return Eigen::Quaterniond::Identity();
}

}  // namespace rscene::render
