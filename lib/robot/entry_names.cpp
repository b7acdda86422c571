#include "robot/entry_names.hpp"

#include "robot/instance.hpp"
#include "robot/kinematics.hpp"

namespace rscene::robot {

void EntryNames::addSide(const Document& doc, std::string sceneDir) { sides_[&doc].sceneDir = std::move(sceneDir); }

std::vector<std::string> EntryNames::operator()(const Document& doc, std::size_t record, std::string_view field) {
  const bool velocity = field == "generalizedVelocity";
  if (!velocity && field != "generalizedCoordinate") return {};
  auto side = sides_.find(&doc);
  if (side == sides_.end()) return {};
  Side& s = side->second;
  if (!s.scene) {
    s.scene = std::make_unique<Scene>();
    SceneOptions so;
    so.sceneDir = s.sceneDir;
    so.bodiesOnly = true;  // the articulated records and their resources
    Diagnostics ignored;   // the diff reports differences, not findings
    buildScene(doc, so, *s.scene, ignored);
    for (const Articulated& a : s.scene->articulated) s.byRecord[static_cast<std::size_t>(a.recordIndex)] = &a;
  }
  auto it = s.byRecord.find(record);
  if (it == s.byRecord.end() || it->second->sourcePath.empty()) return {};
  const Articulated& a = *it->second;
  Diagnostics ignored;
  std::shared_ptr<const Model> model = models_.get(a.sourcePath, loadOptionsOf(a), ignored);
  if (!model) return {};
  robot::Coordinates c;
  if (!robot::makeCoordinates(*model, a.jointOrder, c).empty()) return {};  // names would mislead
  return robot::coordinateNames(*model, c, velocity);
}

}  // namespace rscene::robot
