#include "sim/deformable_solver.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>

namespace rscene::sim {
namespace {

// Reorders constraints so that neighbours in the sequence share no
// particle: a greedy colouring (each constraint takes the first of 64
// colours none of its particles has yet; the rest share a 65th), stable
// within a colour.  Gauss-Seidel then has no chain of dependent updates,
// so the processor overlaps a colour's projections (on a 64 x 64 cloth,
// 34 -> 10 ns a distance constraint); the order stays fixed.
template <class C, class Ids>
void colourOrder(std::vector<C>& constraints, std::size_t particles, Ids ids) {
  std::vector<std::uint64_t> used(particles, 0);
  std::vector<std::pair<int, std::size_t>> order(constraints.size());
  for (std::size_t k = 0; k < constraints.size(); ++k) {
    std::uint64_t taken = 0;
    ids(constraints[k], [&](std::uint32_t p) { taken |= used[p]; });
    int colour = taken == ~std::uint64_t{0} ? 64 : std::countr_one(taken);
    if (colour < 64) ids(constraints[k], [&](std::uint32_t p) { used[p] |= std::uint64_t{1} << colour; });
    order[k] = {colour, k};
  }
  std::sort(order.begin(), order.end());
  std::vector<C> sorted;
  sorted.reserve(constraints.size());
  for (const auto& o : order) sorted.push_back(constraints[o.second]);
  constraints = std::move(sorted);
}

}  // namespace

XpbdDeformable::XpbdDeformable(DeformableModel model) : m_(std::move(model)) {
  colourOrder(m_.distances, m_.positions.size(), [](const DistanceConstraint& c, auto f) {
    f(c.a);
    f(c.b);
  });
  colourOrder(m_.bends, m_.positions.size(), [](const BendConstraint& c, auto f) {
    f(c.a);
    f(c.b);
    f(c.c);
    f(c.d);
  });
  v_.assign(m_.positions.size(), Eigen::Vector3d::Zero());
  lambda_.assign(m_.distances.size() + m_.bends.size(), 0.0);
  finite_ = std::all_of(m_.positions.begin(), m_.positions.end(), [](const auto& p) { return p.allFinite(); });
  for (std::size_t i = 0; i < m_.positions.size(); ++i)
    if (m_.inverseMass[i] != 0) {
      startSum_ += m_.positions[i];
      freeMass_ += m_.particleMass;
    }
}

double XpbdDeformable::startOverlap(SurfaceQuery& surfaces, std::size_t& particle) const {
  particle = 0;
  if (!m_.collidable || !finite_) return 0;
  const double r = m_.collisionRadius;
  Eigen::AlignedBox3d region;
  for (std::size_t i = 0; i < m_.positions.size(); ++i)
    if (m_.inverseMass[i] != 0) region.extend(m_.positions[i]);
  if (region.isEmpty()) return 0;
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(r + 1e-6);
  surfaces.prepare(Eigen::AlignedBox3d(region.min() - grow, region.max() + grow), m_.collisionGroup,
                   m_.collisionMask, m_.contactMaterial);
  double deepest = 0;
  std::vector<SurfaceContact> found;
  for (std::size_t i = 0; i < m_.positions.size(); ++i) {
    if (m_.inverseMass[i] == 0) continue;  // pinned: held where the user put it, pushes nothing
    found.clear();
    surfaces.contacts(m_.positions[i], r, 0, found);
    for (const SurfaceContact& c : found)
      if (c.depth > deepest) {
        deepest = c.depth;
        particle = i;
      }
  }
  return deepest;
}

double XpbdDeformable::pushOut(SurfaceQuery& surfaces, std::size_t& moved) {
  moved = 0;
  if (!m_.collidable || !finite_) return 0;
  const double r = m_.collisionRadius, clear = 1e-6;
  std::vector<Eigen::Vector3d>& x = m_.positions;
  Eigen::AlignedBox3d region;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (m_.inverseMass[i] != 0) region.extend(x[i]);
  if (region.isEmpty()) return 0;
  // A particle moves by at most its overlap (at most r): the region grown
  // by twice the radius holds every surface it meets on its way.
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(2 * r + clear);
  surfaces.prepare(Eigen::AlignedBox3d(region.min() - grow, region.max() + grow), m_.collisionGroup,
                   m_.collisionMask, m_.contactMaterial);
  double deepest = 0;
  std::vector<char> pushed(x.size(), 0);
  std::vector<SurfaceContact> found;
  // Where every overlapping particle meets one flat side (a cloth lying on
  // the ground), the whole body is lifted by the deepest overlap: moving
  // only the particles in it would stretch the constraints to those that
  // are not, and the first substep would throw the body (a coarse cube 3
  // mm in the ground left at 3 m/s).  Pinned particles are held where the
  // user put them, so a body with any is moved particle by particle.
  bool lifted = false;  // `pushed`: the particles that were in it
  const bool pinned = std::any_of(m_.inverseMass.begin(), m_.inverseMass.end(), [](double w) { return w == 0; });
  if (!pinned) {
    const SurfaceContact* first = nullptr;
    SurfaceContact side;
    double lift = 0;
    bool flat = true;
    for (std::size_t i = 0; i < x.size() && flat; ++i) {
      found.clear();
      surfaces.contacts(x[i], r, 0, found);
      for (const SurfaceContact& c : found) {
        if (!(c.depth > 0) || !c.normal.allFinite()) continue;
        if (!first) side = c, first = &side;
        flat = c.normal.dot(side.normal) > 0.9999;
        if (!flat) break;
        lift = std::max(lift, c.depth);
        pushed[i] = 1;
      }
    }
    if (first && flat) {
      for (Eigen::Vector3d& p : x) p += (lift + clear) * side.normal;
      deepest = lift;
      lifted = true;
    } else {
      std::fill(pushed.begin(), pushed.end(), 0);  // particle by particle after all
    }
  }
  // Out of the deepest surface each pass (a corner of two is two passes);
  // a few passes, not a loop that could run on.
  for (int pass = 0; pass < 4; ++pass) {
    bool any = false;
    for (std::size_t i = 0; i < x.size(); ++i) {
      if (m_.inverseMass[i] == 0) continue;  // pinned: held where the user put it
      found.clear();
      surfaces.contacts(x[i], r, 0, found);
      const SurfaceContact* worst = nullptr;
      for (const SurfaceContact& c : found)
        if (c.depth > 0 && c.normal.allFinite() && (!worst || c.depth > worst->depth)) worst = &c;
      if (!worst) continue;
      if (pass == 0 && !lifted) deepest = std::max(deepest, worst->depth);
      x[i] += (worst->depth + clear) * worst->normal;
      pushed[i] = 1;
      any = true;
    }
    if (!any) break;
  }
  moved = static_cast<std::size_t>(std::count(pushed.begin(), pushed.end(), 1));
  // Gravity's work (runaway()) counts from where the particles now start.
  startSum_.setZero();
  for (std::size_t i = 0; i < x.size(); ++i)
    if (m_.inverseMass[i] != 0) startSum_ += x[i];
  finite_ = std::all_of(x.begin(), x.end(), [](const auto& p) { return p.allFinite(); });
  return deepest;
}

// Kinetic energy past twice what gravity and the surfaces gave the free
// particles, plus that of the body moving at 1 m/s (the margin for a body
// at rest): no physics makes it, a stiff or degenerate constraint for the
// (sub)step does.
std::string XpbdDeformable::runaway() const {
  if (!finite_ || !(freeMass_ > 0)) return {};
  const double given = std::max(0.0, gravityWork_) + surfaceWork_;
  if (kinetic_ <= 2 * given + 0.5 * freeMass_) return {};
  char text[320];
  std::snprintf(text, sizeof text,
                "its kinetic energy (%.3g J, %.3g kg at up to %.3g m/s) is past what gravity (%.3g J) and the bodies "
                "it touched (%.3g J) gave it",
                kinetic_, freeMass_, maxSpeed_, gravityWork_, surfaceWork_);
  return text;
}

void XpbdDeformable::step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) {
  if (!(dt > 0) || !finite_) return;  // a body gone non-finite stays as it is: the world reports it
  const double h = dt / m_.substeps;
  // `damping` is the fraction of velocity a world step removes, whatever
  // the substeps: each removes the substeps-th root of what it keeps.
  const double keep = std::pow(1 - m_.damping, 1.0 / m_.substeps);
  const std::size_t n = m_.positions.size();
  std::vector<Eigen::Vector3d>& x = m_.positions;
  for (int sub = 0; sub < m_.substeps; ++sub) {
    previous_ = x;
    for (std::size_t i = 0; i < n; ++i) {
      if (m_.inverseMass[i] == 0) continue;
      v_[i] += gravity * h;
      x[i] += v_[i] * h;
    }
    gatherContacts(surfaces);
    std::fill(lambda_.begin(), lambda_.end(), 0.0);
    for (int it = 0; it < m_.iterations; ++it) {
      solveDistances(h);
      solveBends(h);
      solveContacts();
    }
    if (m_.iterations == 0) solveContacts();
    applyFriction(surfaces, h, dt);
    for (std::size_t i = 0; i < n; ++i)
      v_[i] = m_.inverseMass[i] == 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d((x[i] - previous_[i]) / h * keep);
  }
  double fastest = 0, speeds2 = 0;
  bool ok = true;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    ok = ok && x[i].allFinite() && v_[i].allFinite();
    fastest = std::max(fastest, v_[i].norm());
    if (m_.inverseMass[i] == 0) continue;
    speeds2 += v_[i].squaredNorm();
    sum += x[i];
  }
  finite_ = ok;
  maxSpeed_ = ok ? fastest : INFINITY;
  kinetic_ = 0.5 * m_.particleMass * speeds2;
  gravityWork_ = m_.particleMass * gravity.dot(sum - startSum_);
}

// Contacts of each free particle's sphere, looked for around where it
// started the substep within the distance it travels: a surface it may
// reach during the substep is a half-space constraint for the iterations.
void XpbdDeformable::gatherContacts(SurfaceQuery& surfaces) {
  contacts_.clear();
  if (!m_.collidable || m_.positions.empty()) return;
  const double r = m_.collisionRadius;
  Eigen::AlignedBox3d region;
  double travel = 0;
  for (std::size_t i = 0; i < m_.positions.size(); ++i) {
    if (m_.inverseMass[i] == 0) continue;  // pinned: a static proxy
    region.extend(previous_[i]);
    region.extend(m_.positions[i]);
    travel = std::max(travel, (m_.positions[i] - previous_[i]).norm());
  }
  if (region.isEmpty()) return;
  // A resting particle keeps its contact: a slack of half the radius (and
  // a micrometre for radius 0) over the distance travelled.
  const double slack = 0.5 * r + 1e-6;
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(r + travel + slack);
  surfaces.prepare(Eigen::AlignedBox3d(region.min() - grow, region.max() + grow), m_.collisionGroup,
                   m_.collisionMask, m_.contactMaterial);
  for (std::uint32_t i = 0; i < m_.positions.size(); ++i) {
    if (m_.inverseMass[i] == 0) continue;
    found_.clear();
    double margin = (m_.positions[i] - previous_[i]).norm() + slack;
    surfaces.contacts(previous_[i], r, margin, found_);
    for (const SurfaceContact& c : found_) contacts_.push_back({i, c, 0});
  }
}

void XpbdDeformable::solveDistances(double h) {
  std::vector<Eigen::Vector3d>& x = m_.positions;
  const std::vector<double>& w = m_.inverseMass;
  const double invH2 = 1 / (h * h);
  for (std::size_t k = 0; k < m_.distances.size(); ++k) {
    const DistanceConstraint& c = m_.distances[k];
    const double wsum = w[c.a] + w[c.b];
    if (wsum == 0) continue;
    Eigen::Vector3d d = x[c.a] - x[c.b];
    const double len = d.norm();
    if (!(len > 1e-12)) continue;  // coincident: no direction to push along
    const double C = len - c.rest, alpha = c.compliance * invH2;
    // XPBD (Macklin et al. 2016): the multiplier accumulates over the
    // iterations, so the compliance holds whatever their number; PBD
    // restarts it each time, which stiffens with more iterations.
    const double dl = m_.xpbd ? (-C - alpha * lambda_[k]) / (wsum + alpha) : -C / (wsum + alpha);
    lambda_[k] += dl;
    d *= dl / len;
    x[c.a] += w[c.a] * d;
    x[c.b] -= w[c.b] * d;
  }
}

void XpbdDeformable::solveBends(double h) {
  std::vector<Eigen::Vector3d>& x = m_.positions;
  const std::vector<double>& w = m_.inverseMass;
  const double invH2 = 1 / (h * h);
  const std::size_t base = m_.distances.size();
  Eigen::Vector3d g[4];
  for (std::size_t k = 0; k < m_.bends.size(); ++k) {
    const BendConstraint& c = m_.bends[k];
    const std::uint32_t id[4] = {c.a, c.b, c.c, c.d};
    if (w[c.a] + w[c.b] + w[c.c] + w[c.d] == 0) continue;
    double angle = 0;
    if (!dihedralGradient(x[c.a], x[c.b], x[c.c], x[c.d], g, &angle)) continue;
    double C = angle - c.restAngle;  // the shorter way round: both angles are in [-pi, pi]
    if (C > M_PI) C -= 2 * M_PI;
    if (C < -M_PI) C += 2 * M_PI;
    const double alpha = c.compliance * invH2;
    double denom = alpha;
    for (int q = 0; q < 4; ++q) denom += w[id[q]] * g[q].squaredNorm();
    if (!(denom > 0)) continue;
    double& lambda = lambda_[base + k];
    const double dl = m_.xpbd ? (-C - alpha * lambda) / denom : -C / denom;
    lambda += dl;
    for (int q = 0; q < 4; ++q) x[id[q]] += w[id[q]] * dl * g[q];
  }
}

// Each contact is the half-space beyond its surface point, offset by the
// particle's radius: a particle inside is moved out along the normal.
void XpbdDeformable::solveContacts() {
  const double r = m_.collisionRadius;
  for (Contact& c : contacts_) {
    Eigen::Vector3d& x = m_.positions[c.particle];
    const double C = (x - c.surface.point).dot(c.surface.normal) - r;
    if (C >= 0) continue;
    x -= C * c.surface.normal;
    c.pushed -= C;
  }
}

// Coulomb friction on the substep's displacement relative to the surface
// (Macklin et al. 2014): a tangential slip shorter than friction x the
// normal push is undone (sticking), a longer one is shortened by it.  The
// particle's momentum change from the contact is the reaction's impulse.
void XpbdDeformable::applyFriction(SurfaceQuery& surfaces, double h, double dt) {
  for (Contact& c : contacts_) {
    if (!(c.pushed > 0)) continue;
    Eigen::Vector3d& x = m_.positions[c.particle];
    const Eigen::Vector3d& nrm = c.surface.normal;
    const Eigen::Vector3d surfaceVelocity = surfaces.velocity(c.surface.body, c.surface.point);
    Eigen::Vector3d slip = (x - previous_[c.particle]) - surfaceVelocity * h;
    slip -= slip.dot(nrm) * nrm;
    const double len = slip.norm(), limit = std::max(0.0, c.surface.friction) * c.pushed;
    Eigen::Vector3d fix = len <= limit ? Eigen::Vector3d(-slip) : Eigen::Vector3d(-slip * (limit / len));
    if (!fix.allFinite()) fix.setZero();
    x += fix;
    if (c.surface.body >= 0) {
      const Eigen::Vector3d impulse = m_.particleMass * (nrm * c.pushed + fix) / h;
      // What the moving surface gave the particle (J): the energy budget of runaway().
      surfaceWork_ += std::max(0.0, impulse.dot(surfaceVelocity));
      surfaces.addForce(c.surface.body, c.surface.point, -impulse / dt);
    }
  }
}

}  // namespace rscene::sim
