#include "sim/deformable_body.hpp"

#include "scene/deformable_model.hpp"
#include "sim/deformable_solver.hpp"

namespace rscene::sim {

std::unique_ptr<DeformableBody> DeformableBody::create(const Deformable& record, const asset::ObjSurface& surface,
                                                       std::string& error, std::string& errorField) {
  DeformableModel model;
  if (!buildDeformableModel(record, surface, model, error, errorField)) return nullptr;
  return std::make_unique<XpbdDeformable>(std::move(model));
}

}  // namespace rscene::sim
