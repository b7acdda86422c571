#include "sim/particle_systems.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/codes.hpp"
#include "core/text.hpp"
#include "scene/reader.hpp"

namespace rscene::sim {

bool ParticleSystems::create(const Scene& scene, const Document* doc, asset::AssetCache& assets,
                             Diagnostics& diagnostics) {
  bool ok = true;
  timeStep_ = scene.timeStep;
  for (const Deformable& d : scene.deformables) {
    asset::ObjSurface surface;
    std::string error, field;
    if (!asset::loadObjSurface(assets.fileSystem(), d.meshPath, surface, &error)) {
      reportAt(doc, d.recordIndex, "meshPath", particle_code::kDeformableMesh,
             "deformable '" + d.path + "': mesh " + d.meshPath + ": " + error, diagnostics);
      ok = false;
      continue;
    }
    std::unique_ptr<DeformableBody> body = DeformableBody::create(d, surface, error, field);
    if (!body) {
      reportAt(doc, d.recordIndex, field, particle_code::kDeformable, "deformable '" + d.path + "': " + error,
             diagnostics);
      ok = false;
      continue;
    }
    deformables_.push_back({d.recordIndex, d.path, std::move(body)});
  }
  for (const Granular& g : scene.granulars) {
    std::vector<GranularFinding> findings;
    std::unique_ptr<GranularBody> body = GranularBody::create(g, scene.timeStep, findings);
    // Its warnings (RS7086) are checkScene()'s to report, which ran the
    // same granularSetup() before the world was built.
    for (const GranularFinding& f : findings)
      if (f.error) reportAt(doc, g.recordIndex, f.field, f.code, f.message, diagnostics);
    if (!body) {
      ok = false;
      continue;
    }
    Granular record = g;
    record.positions.clear();
    record.radii.clear();
    granulars_.push_back({g.recordIndex, g.path, g.world, std::move(body), std::move(record)});
  }
  return ok;
}

void ParticleSystems::step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) {
  auto start = std::chrono::steady_clock::now();
  for (DeformableEntry& d : deformables_) d.body->step(dt, gravity, surfaces);
  for (GranularEntry& g : granulars_) g.body->step(dt, gravity, surfaces);
  stepSeconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

GranularStats ParticleSystems::granularStats() const {
  GranularStats sum;
  for (const GranularEntry& g : granulars_) {
    const GranularStats& s = g.body->stats();
    sum.substepsPerStep = std::max(sum.substepsPerStep, s.substepsPerStep);
    sum.particleSubsteps += s.particleSubsteps;
    sum.neighbourBuilds += s.neighbourBuilds;
    sum.pairs += s.pairs;
    sum.contacts += s.contacts;
    sum.surfaceContacts += s.surfaceContacts;
    sum.neighbourSeconds += s.neighbourSeconds;
    sum.contactSeconds += s.contactSeconds;
    sum.surfaceSeconds += s.surfaceSeconds;
    sum.integrateSeconds += s.integrateSeconds;
    sum.maxPenetration = std::max(sum.maxPenetration, s.maxPenetration);
  }
  return sum;
}

std::size_t ParticleSystems::particles() const {
  std::size_t n = 0;
  for (const DeformableEntry& d : deformables_) n += d.body->positions().size();
  for (const GranularEntry& g : granulars_) n += g.body->positions().size();
  return n;
}

bool ParticleSystems::atRest(double speed) const {
  for (const DeformableEntry& d : deformables_)
    if (!(d.body->maxSpeed() < speed)) return false;
  for (const GranularEntry& g : granulars_)
    if (!(g.body->maxSpeed() < speed)) return false;
  return true;
}

std::vector<ParticleState> ParticleSystems::states() const {
  std::vector<ParticleState> out;
  out.reserve(deformables_.size() + granulars_.size());
  for (const DeformableEntry& d : deformables_) out.push_back({d.recordIndex, d.path, false, &d.body->positions()});
  for (const GranularEntry& g : granulars_) out.push_back({g.recordIndex, g.path, true, &g.body->positions()});
  return out;
}

std::optional<std::pair<int, std::string>> ParticleSystems::nonFinite() const {
  for (const DeformableEntry& d : deformables_)
    if (!d.body->finite()) return std::pair{d.recordIndex, d.path};
  for (const GranularEntry& g : granulars_)
    if (!g.body->finite()) return std::pair{g.recordIndex, g.path};
  return std::nullopt;
}

std::vector<ParticleSystems::DeformableCost> ParticleSystems::deformableCosts() const {
  std::vector<DeformableCost> out;
  for (const DeformableEntry& d : deformables_) out.push_back({d.recordIndex, d.path, d.body->workPerStep()});
  return out;
}

bool ParticleSystems::checkDeformableStarts(SurfaceQuery& surfaces, const Document* doc,
                                            Diagnostics& diagnostics) {
  bool ok = true;
  for (DeformableEntry& d : deformables_) {
    std::size_t particle = 0;
    const double depth = d.body->startOverlap(surfaces, particle), r = d.body->collisionRadius();
    if (!(depth > 1.5 * r + 1e-6)) {
      if (!(depth > 0)) continue;
      // Centres up to half the radius inside (a cloth laid on the ground
      // included): out before the first step, where the first substep
      // would push it out at depth / substep (5 mm in 1 ms is 5 m/s: a
      // launch the divergence check stops, RS7024).
      std::size_t moved = 0;
      const double removed = d.body->pushOut(surfaces, moved);
      if (removed > 1e-6)
        reportAt(doc, d.recordIndex, "position", rs::RS7016,
                 "deformable '" + d.path + "': " + std::to_string(moved) + (moved == 1 ? " particle starts" : " particles start") +
                     " inside the ground or another body, up to " + roundedNumber(removed, 3) +
                     " m deep (its sphere of collisionRadius " + roundedNumber(r, 6) +
                     " m overlapping it); moved out along the contact normal before the first step",
                 diagnostics, Severity::Warning,
                 "place the deformable at least its collisionRadius above the ground and clear of other bodies");
      continue;
    }
    const Eigen::Vector3d& at = d.body->positions()[particle];
    reportAt(doc, d.recordIndex, "position", rs::RS7077,
             "deformable '" + d.path + "': particle " + std::to_string(particle) + " at (" + roundedNumber(at.x(), 6) +
                 ", " + roundedNumber(at.y(), 6) + ", " + roundedNumber(at.z(), 6) + ") starts " +
                 (depth > r ? roundedNumber(depth - r, 6) + " m inside" : roundedNumber(r - depth, 6) + " m above the surface of") +
                 " the ground or another body, its sphere of collisionRadius " + roundedNumber(r, 6) + " m overlapping by " +
                 roundedNumber(depth, 6) + " m (its centre more than half the radius inside); pushing it out would "
                 "throw the body and what it touches",
             diagnostics, Severity::Error,
             "place the deformable clear of the other bodies (at least its collisionRadius above the ground)");
    ok = false;
  }
  return ok;
}

std::vector<ParticleSystems::GranularCost> ParticleSystems::granularCosts() const {
  std::vector<GranularCost> out;
  for (const GranularEntry& g : granulars_) {
    GranularCost c{g.recordIndex, g.path, g.body->positions().size(), g.body->candidatePairs(),
                   g.body->stats().substepsPerStep, 0};
    c.workPerStep = static_cast<double>(c.substeps) * static_cast<double>(c.grains + c.pairs);
    out.push_back(std::move(c));
  }
  return out;
}

GranularStartDepth ParticleSystems::startDepth(const GranularEntry& g, SurfaceQuery& surfaces) {
  GranularStartDepth out;
  const std::vector<Eigen::Vector3d>& x = g.body->positions();
  const std::vector<double>& r = g.body->radii();
  if (x.empty() || g.body->fixed()) return out;
  Eigen::AlignedBox3d region;
  double rMax = 0;
  for (std::size_t i = 0; i < x.size(); ++i) region.extend(x[i]), rMax = std::max(rMax, r[i]);
  region.min().array() -= rMax;
  region.max().array() += rMax;
  surfaces.prepare(region, 1, ~std::uint64_t{0}, "");  // as the solver prepares them
  std::vector<SurfaceContact> found;
  double worstExcess = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    found.clear();
    surfaces.contacts(x[i], r[i], 0, found);
    double depth = 0;
    for (const SurfaceContact& c : found)
      if (c.normal.allFinite() && c.depth > depth) depth = c.depth;
    const double tol = granularStartDepthTolerance(g.body->material(), r[i]);
    if (!(depth > tol * (1 + 1e-9))) continue;
    ++out.count;
    if (depth - tol > worstExcess) {
      worstExcess = depth - tol;
      out.worst = i, out.depth = depth, out.tolerance = tol, out.at = x[i];
    }
  }
  return out;
}

bool ParticleSystems::checkGranularStarts(SurfaceQuery& surfaces, const Document* doc, Diagnostics& diagnostics) const {
  bool ok = true;
  for (const GranularEntry& g : granulars_) {
    const GranularStartDepth deep = startDepth(g, surfaces);
    if (!deep.count) continue;
    const ParticleFinding f = granularStartDepthFinding(g.record, deep, "the ground or another body");
    reportAt(doc, g.recordIndex, f.field, f.code, f.message, diagnostics);
    ok = false;
  }
  return ok;
}

std::optional<ParticleSystems::Runaway> ParticleSystems::deformableRunaway() const {
  for (const DeformableEntry& d : deformables_)
    if (std::string why = d.body->runaway(); !why.empty()) return Runaway{d.recordIndex, d.path, std::move(why)};
  return std::nullopt;
}

std::optional<ParticleFailure> ParticleSystems::failure() const {
  for (const GranularEntry& g : granulars_)
    if (const auto& f = g.body->failure()) {
      ParticleFailure out{g.recordIndex, g.path, *f};
      out.failure.message = "granular " + g.path + ": " + out.failure.message;
      return out;
    }
  return std::nullopt;
}

std::vector<Eigen::Vector3d> ParticleSystems::local(const GranularEntry& g) {
  const Pose toRecord = g.frame.inverse();
  std::vector<Eigen::Vector3d> out;
  out.reserve(g.body->positions().size());
  for (const Eigen::Vector3d& p : g.body->positions()) {
    Eigen::Vector3d x = (toRecord * Pose{p, Eigen::Quaterniond::Identity()}).position;
    for (int k = 0; k < 3; ++k)
      if (x[k] == 0) x[k] = 0.0;  // no "-0"
    out.push_back(x);
  }
  return out;
}

namespace {

// The one velocity writeBack() gives a granular record: its grains' mean
// velocity now, in the record's frame.
Eigen::Vector3d meanVelocity(const GranularBody& body, const Pose& frame) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : body.velocities()) mean += v;
  if (!body.velocities().empty()) mean /= static_cast<double>(body.velocities().size());
  return frame.orientation.conjugate() * mean;
}

}  // namespace

std::optional<ParticleFailure> ParticleSystems::unwritable(SurfaceQuery* surfaces) const {
  for (const GranularEntry& g : granulars_) {
    if (g.body->positions().empty() || g.record.fixed) continue;  // written as they were read
    Granular settled = g.record;
    settled.positions = local(g);
    settled.radii = g.body->radii();
    settled.velocity = meanVelocity(*g.body, g.frame);  // past 1e4 m/s: RS7088 when reloaded
    settled.angularVelocity.setZero();
    std::vector<ParticleFinding> findings;
    granularSetup(settled, timeStep_, findings, false);
    for (const ParticleFinding& f : findings) {
      if (!f.error) continue;
      const bool overlap = f.code == std::string_view(particle_code::kOverlap);
      std::string rule = f.message;
      const std::string prefix = "granular " + g.path + ": ";
      if (rule.compare(0, prefix.size(), prefix) == 0) rule.erase(0, prefix.size());
      GranularFailure why{particle_code::kLeftBounds, overlap ? "normalStiffness" : "",
                          "granular " + g.path + ": at the end of the run its grains are where the scene model "
                          "refuses them (" + rule + " [" + f.code + "]), so the scene written would not load; "
                          "nothing was written",
                          overlap ? "the contact law is too soft for the bed's weight: raise normalStiffness (or "
                                    "lower density or the bed's height)"
                                  : "look at the record's velocity and at what launches the grains"};
      return ParticleFailure{g.recordIndex, g.path, std::move(why)};
    }
    if (surfaces) {
      const GranularStartDepth deep = startDepth(g, *surfaces);
      if (deep.count) {
        std::string rule = granularStartDepthFinding(g.record, deep, "the ground or another body", false).message;
        const std::string prefix = "granular " + g.path + ": ";
        if (rule.compare(0, prefix.size(), prefix) == 0) rule.erase(0, prefix.size());
        GranularFailure why{particle_code::kLeftBounds, "normalStiffness",
                            "granular " + g.path + ": at the end of the run its grains are where a run would not "
                            "start them (" + rule + " [" + particle_code::kStartsInside + "]), so the scene written "
                            "would not load; nothing was written",
                            "the contact law is too soft for the load on it: raise normalStiffness (or lower density, "
                            "the bed's height or what presses on it)"};
        return ParticleFailure{g.recordIndex, g.path, std::move(why)};
      }
    }
  }
  return std::nullopt;
}

void ParticleSystems::writeBack(Document& doc) const {
  std::string positions, radii;
  for (const GranularEntry& g : granulars_) {
    positions.clear();
    radii.clear();
    const std::vector<double>& r = g.body->radii();
    if (g.body->positions().empty()) continue;  // an empty bed stays as written
    const std::vector<Eigen::Vector3d> p = local(g);
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (i) {
        positions += ';';
        radii += ',';
      }
      for (int k = 0; k < 3; ++k) {
        if (k) positions += ',';
        appendNumber(positions, p[i][k]);
      }
      appendNumber(radii, r[i]);
    }
    doc.setKey(static_cast<std::size_t>(g.recordIndex), "positions", positions);
    doc.setKey(static_cast<std::size_t>(g.recordIndex), "radii", radii);
    // The record has one velocity for all its grains (its start velocity,
    // in its frame): the grains' mean velocity now, so a bed that came to
    // rest reloads at rest instead of launched again; the grains' own
    // spins are not kept (angularVelocity becomes 0).
    const Eigen::Vector3d mean = meanVelocity(*g.body, g.frame);
    std::string velocity;
    for (int k = 0; k < 3; ++k) {
      if (k) velocity += ',';
      appendNumber(velocity, mean[k] == 0 ? 0.0 : mean[k]);
    }
    // (A record without them starts its grains at rest when reloaded.)
    const Record& rec = doc.records[static_cast<std::size_t>(g.recordIndex)];
    auto has = [&](std::string_view key) {
      for (std::uint32_t j = 0; j < rec.fieldCount; ++j) {
        const Field& f = doc.fields[rec.firstField + j];
        if (f.isKey() && doc.text(f.key) == key) return true;
      }
      return false;
    };
    if (has("velocity")) doc.setKey(static_cast<std::size_t>(g.recordIndex), "velocity", velocity);
    if (has("angularVelocity")) doc.setKey(static_cast<std::size_t>(g.recordIndex), "angularVelocity", "0,0,0");
  }
}

}  // namespace rscene::sim
