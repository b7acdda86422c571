#include "sim/granular_dem.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/text.hpp"
#include "sim/granular_contact.hpp"
#include "sim/granular_pairs.hpp"

namespace rscene::sim {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point& t) {
  Clock::time_point now = Clock::now();
  double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

// The tangential spring of a grain's contact with a surface, found again
// at the next substep by (body, ordinal): the ordinal-th contact of this
// grain with that body in the query's order.  A grain has a handful.
struct SurfaceHistory {
  int body = -1;
  int ordinal = 0;
  GranularHistory springs;
};

class GranularDem final : public GranularBody {
 public:
  explicit GranularDem(GranularSetup p)
      : m_(p.material), substeps_(p.substeps), maxSubstep_(p.maxSubstep), fixed_(p.fixed), x_(std::move(p.positions)),
        r_(std::move(p.radii)) {
    const GranularMaterial& m = m_;
    const std::size_t n = x_.size();
    v_.assign(n, p.velocity);
    w_.assign(n, p.angularVelocity);
    f_.assign(n, Eigen::Vector3d::Zero());
    t_.assign(n, Eigen::Vector3d::Zero());
    invMass_.resize(n);
    invInertia_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      double mass = m.density * 4.0 / 3.0 * M_PI * r_[i] * r_[i] * r_[i];
      totalMass_ += mass;
      invMass_[i] = fixed_ ? 0 : 1 / mass;
      invInertia_[i] = fixed_ ? 0 : 1 / (0.4 * mass * r_[i] * r_[i]);  // solid sphere
      rMax_ = std::max(rMax_, r_[i]);
    }
    // The skin trades list size against rebuilds: a fifth of the largest
    // radius is a few substeps of travel for a grain falling at m/s.
    skin_ = 0.2 * rMax_;
    reach_ = m_.cohesionMaxDistance + skin_;
    stats_.substepsPerStep = substeps_;
    surfaceStart_.assign(n + 1, 0);
    speed_ = fixed_ ? 0 : p.velocity.norm();
    maxPairs_ = kMaxGranularPairsPerGrain * n + kGranularPairSlack;
    // Energy the check lets pass on top of the budget (see checkEnergy()):
    // every grain a rise of its own radius.
    for (std::size_t i = 0; i < n; ++i) energyFloor_ += r_[i] / invMass_[i];
    if (fixed_) energyFloor_ = 0;
    // The pair list now, so that the run's cost is known before its first
    // step (a list past its cap stops the run at that step, RS7085).
    if (!fixed_ && n) rebuild();
  }

  void step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) override {
    if (x_.empty() || !(dt > 0) || failure_) return;
    // create() chose substeps_ for the scene's time step; a caller stepping
    // longer steps gets what stability needs for them (the same rule).
    int n = substeps_;
    const double needed = std::ceil(dt / maxSubstep_ - 1e-9);
    if (needed > n) n = static_cast<int>(std::min<double>(kMaxSubsteps, needed));
    stats_.substepsPerStep = n;
    const double h = dt / n;
    ++steps_;  // this one, for the messages
    time_ += dt;
    for (int s = 0; s < n && !failure_; ++s) substep(h, h / dt, gravity, surfaces, s == n - 1 || (steps_ == 1 && s == 0));
    finite_ = true;
    for (std::size_t i = 0; i < x_.size() && finite_; ++i)
      finite_ = x_[i].allFinite() && v_[i].allFinite() && w_[i].allFinite();
    if (!finite_ || failure_ || fixed_) return;  // not finite: RS7024
    for (std::size_t i = 0; i < x_.size(); ++i)
      if (!(x_[i].cwiseAbs().maxCoeff() <= kMaxGranularCoordinate)) {
        fail(particle_code::kLeftBounds, "",
             "grain " + std::to_string(i) + " is past 1e9 m " + when() + " (at " + roundedNumber(x_[i].norm(), 4) +
                 " m, " + roundedNumber(v_[i].norm(), 4) +
                 " m/s): a scene written with it would be refused",
             "grains this fast or this far are not a scene: look at the record's velocity, or at forces that "
             "launch them (cohesion, starting overlaps, the time step)");
        return;
      }
  }

  const std::vector<Eigen::Vector3d>& positions() const override { return x_; }
  const std::vector<Eigen::Vector3d>& velocities() const override { return v_; }
  const std::vector<double>& radii() const override { return r_; }
  double totalMass() const override { return totalMass_; }
  double maxSpeed() const override { return speed_; }
  bool finite() const override { return finite_; }
  const GranularStats& stats() const override { return stats_; }
  const std::optional<GranularFailure>& failure() const override { return failure_; }
  const GranularMaterial& material() const override { return m_; }
  bool fixed() const override { return fixed_; }
  std::size_t candidatePairs() const override { return pairs_.size(); }

 private:
  // `measure`: the mechanical energy of the state this substep starts from
  // is added up on the way (the first substep of the run and the last of
  // every step) and checked against the budget.
  void substep(double h, double share, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces, bool measure) {
    Clock::time_point t = Clock::now();
    if (!fixed_ && (!built_ || drift_ > 0.5 * skin_)) rebuild();
    if (failure_) return;
    stats_.neighbourSeconds += since(t);
    measure = measure && !fixed_;
    potential_ = 0, elastic_ = 0, surfaceElastic_ = 0;

    for (std::size_t i = 0; i < x_.size(); ++i) f_[i].setZero(), t_[i].setZero();
    stats_.maxPenetration = 0;
    pairForces(h, measure);
    stats_.contactSeconds += since(t);

    surfaceForces(h, share, surfaces, measure);
    stats_.surfaceSeconds += since(t);

    if (measure) checkEnergy(gravity);
    integrate(h, gravity);
    stats_.integrateSeconds += since(t);
    stats_.particleSubsteps += x_.size();
  }

  std::string when() const {
    char at[96];
    std::snprintf(at, sizeof at, "at step %llu (t = %.6g s)", static_cast<unsigned long long>(steps_), time_);
    return at;
  }

  void fail(const char* code, std::string field, std::string message, std::string hint) {
    failure_ = GranularFailure{code, std::move(field), std::move(message) + "; the simulation stopped and nothing was written",
                               std::move(hint)};
  }

  // Kinetic energy (translation and rotation), gravity's potential and the
  // potential_ of the contacts' springs and the cohesion wells: what a
  // stable solver can only lose (damping, friction) unless a body works on
  // the grains (bodyWork_, counted from the surfaces' velocities).  A
  // solver past its stability limit gains it from nothing: past the start
  // plus the work plus half the energy in motion now (the integrator's own
  // oscillation about the true energy) plus every grain rising its own
  // radius, the run stops naming the likely cause.
  void checkEnergy(const Eigen::Vector3d& gravity) {
    double kinetic = 0, height = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      const double mass = 1 / invMass_[i];
      kinetic += 0.5 * mass * v_[i].squaredNorm() + 0.5 / invInertia_[i] * w_[i].squaredNorm();
      height -= mass * gravity.dot(x_[i]);
    }
    const double energy = kinetic + height + potential_;
    if (!std::isfinite(energy)) return;  // RS7024's business
    if (!measured_) {
      measured_ = true;
      // The springs of grains starting inside the ground or a body are no
      // budget: grains deeper than granularStartDepthTolerance() were
      // refused (RS7091), and what is left would otherwise let a solver
      // throw them with energy it never had.
      startEnergy_ = energy - surfaceElastic_;
      bodyWork_ = 0;
      return;
    }
    const double gained = energy - startEnergy_ - bodyWork_;
    const double slack = 0.5 * (kinetic + std::max(0.0, elastic_)) + energyFloor_ * std::max(gravity.norm(), 9.81);
    if (!(gained > slack)) return;
    const GranularMaterial& m = m_;
    const bool cohesive = m.cohesionStiffness > 0 && m.cohesionMaxDistance > 0;
    fail(particle_code::kEnergy, cohesive ? "cohesionStiffness" : "substeps",
         "the grains' energy grew by " + roundedNumber(gained, 3) + " J " + when() + " (from " +
             roundedNumber(startEnergy_, 3) + " J to " + roundedNumber(energy, 3) + " J with " +
             roundedNumber(bodyWork_, 3) + " J of work by bodies; fastest grain " + roundedNumber(speed_, 3) +
             " m/s): the solver is unstable",
         std::string(cohesive ? "likely the cohesion: lower cohesionStiffness or cohesionMaxDistance (a grain in "
                                "range of many others is stiffer than one pair); "
                              : "") +
             "or grains starting in overlap, or too long a time step for normalStiffness: raise substeps or "
             "shorten time_step");
  }

  void rebuild() {
    if (!pairs_.build(x_, r_, rMax_, reach_, maxPairs_)) {
      fail(particle_code::kTooManyGrainPairs, m_.cohesionMaxDistance > 0 ? "cohesionMaxDistance" : "",
           "more than " + std::to_string(maxPairs_) + " candidate pairs (" + std::to_string(kMaxGranularPairsPerGrain) +
               " per grain) " + when() + ": the grains are pressed into each other",
           "grains that do not overlap by more than half their radii have at most 9 pairs each; look for a "
           "contact law too soft for the load (normalStiffness) or grains thrown into each other");
      return;
    }
    anchor_ = x_;
    drift_ = 0;
    built_ = true;
    ++stats_.neighbourBuilds;
    stats_.pairs = pairs_.size();
  }

  // Energy stored in a contact: the normal spring at depth d (linear or
  // Hertz) and the tangential and rolling springs.
  double springEnergy(double depth, double reff, const GranularHistory& hist) const {
    const GranularMaterial& m = m_;
    double e = 0.5 * m.kt * hist.slide.squaredNorm() + 0.5 * m.kt * reff * reff * hist.roll.squaredNorm();
    if (depth > 0) e += m.hertz ? 0.4 * m.kn * depth * depth * std::sqrt(depth / reff) : 0.5 * m.kn * depth * depth;
    return e;
  }
  // The cohesion well at a surface gap (granular_contact.hpp's law), zero
  // past the cut-off: -kc gmax^2 / 6 in contact.
  double cohesionEnergy(double gap) const {
    const double kc = m_.cohesionStiffness, gmax = m_.cohesionMaxDistance;
    if (!(kc > 0) || !(gmax > 0) || gap >= gmax) return 0;
    const double g = std::max(0.0, gap);
    return -kc * (gmax * gmax / 6 - g * g / 2 + g * g * g / (3 * gmax));
  }

  void pairForces(double h, bool measure) {
    std::size_t touching = 0;
    GranularContact c;
    for (std::size_t k = 0; k < pairs_.size(); ++k) {
      const std::uint32_t a = pairs_.i[k], b = pairs_.j[k];
      const Eigen::Vector3d d = x_[a] - x_[b];
      const double dist2 = d.squaredNorm(), range = r_[a] + r_[b] + m_.cohesionMaxDistance;
      if (dist2 > range * range) {  // most listed pairs, the skin's: no square root for them
        pairs_.history[k] = {};
        continue;
      }
      const double dist = std::sqrt(dist2);
      c.depth = r_[a] + r_[b] - dist;
      c.n = dist > 0 ? Eigen::Vector3d(d / dist) : Eigen::Vector3d::UnitZ();
      c.ra = r_[a];
      c.rb = r_[b];
      c.reff = r_[a] * r_[b] / (r_[a] + r_[b]);
      c.friction = m_.friction;  // one material per record: RaiSim uses a material's own friction for equal ids
      c.va = v_[a], c.vb = v_[b], c.wa = w_[a], c.wb = w_[b];
      if (measure) {
        const double e = springEnergy(c.depth, c.reff, pairs_.history[k]);
        potential_ += e + cohesionEnergy(-c.depth);
        elastic_ += e;
      }
      GranularContactForce out = granularContactForce(m_, c, h, pairs_.history[k]);
      f_[a] += out.force;
      f_[b] -= out.force;
      t_[a] += out.torqueA;
      t_[b] += out.torqueB;
      if (c.depth > 0) ++touching, stats_.maxPenetration = std::max(stats_.maxPenetration, c.depth);
    }
    stats_.contacts = touching;
  }

  void surfaceForces(double h, double share, SurfaceQuery& surfaces, bool measure) {
    Eigen::AlignedBox3d region;
    for (const Eigen::Vector3d& p : x_) region.extend(p);
    // Where the grains can be during this substep, and their radius.
    const double grow = rMax_ + speed_ * h + skin_;
    region.min().array() -= grow;
    region.max().array() += grow;
    surfaces.prepare(region, 1, ~std::uint64_t{0}, "");

    previous_.swap(histories_);
    previousStart_.swap(surfaceStart_);
    histories_.clear();
    surfaceStart_.assign(x_.size() + 1, 0);
    std::size_t count = 0;
    GranularContact c;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      surfaceStart_[i] = static_cast<std::uint32_t>(histories_.size());
      found_.clear();
      surfaces.contacts(x_[i], r_[i], 0, found_);
      for (std::size_t q = 0; q < found_.size(); ++q) {
        const SurfaceContact& s = found_[q];
        if (!(s.depth > 0) || !s.normal.allFinite()) continue;
        int ordinal = 0;
        for (std::size_t e = surfaceStart_[i]; e < histories_.size(); ++e) ordinal += histories_[e].body == s.body;
        SurfaceHistory hist{s.body, ordinal, {}};
        for (std::size_t e = previousStart_[i]; e < previousStart_[i + 1]; ++e)
          if (previous_[e].body == s.body && previous_[e].ordinal == ordinal) hist.springs = previous_[e].springs;
        c.n = s.normal;
        c.depth = s.depth;
        c.ra = r_[i];
        c.rb = 0;
        c.reff = r_[i];
        // Geometric mean of the grain's and the surface's friction, as
        // RaiSim mixes a particle material with its boundary material.
        c.friction = std::sqrt(m_.friction * std::max(0.0, s.friction));
        c.va = v_[i], c.wa = w_[i];
        c.vb = s.body >= 0 ? surfaces.velocity(s.body, s.point) : Eigen::Vector3d::Zero();
        c.wb.setZero();
        if (measure) {
          const double e = springEnergy(c.depth, c.reff, hist.springs);
          potential_ += e;
          elastic_ += e;
          surfaceElastic_ += e;
        }
        GranularContactForce out = granularContactForce(m_, c, h, hist.springs);
        f_[i] += out.force;
        t_[i] += out.torqueA;
        // What a moving body can give the grain this substep (an upper
        // bound: the force on the grain along the body's motion).
        if (s.body >= 0 && !fixed_) bodyWork_ += std::max(0.0, out.force.dot(c.vb)) * h;
        // The body takes the opposite force, averaged over the world step.
        if (s.body >= 0) surfaces.addForce(s.body, s.point, -out.force * share);
        histories_.push_back(hist);
        stats_.maxPenetration = std::max(stats_.maxPenetration, s.depth);
        ++count;
      }
    }
    surfaceStart_[x_.size()] = static_cast<std::uint32_t>(histories_.size());
    stats_.surfaceContacts = count;
  }

  void integrate(double h, const Eigen::Vector3d& gravity) {
    if (fixed_) return;
    double speed2 = 0, drift2 = 0;
    for (std::size_t i = 0; i < x_.size(); ++i) {
      v_[i] += h * (f_[i] * invMass_[i] + gravity);
      w_[i] += h * invInertia_[i] * t_[i];
      x_[i] += h * v_[i];
      speed2 = std::max(speed2, v_[i].squaredNorm());
      drift2 = std::max(drift2, (x_[i] - anchor_[i]).squaredNorm());
    }
    speed_ = std::sqrt(speed2);
    drift_ = std::sqrt(drift2);
  }

  GranularMaterial m_;
  int substeps_;
  double maxSubstep_;
  bool fixed_;
  std::vector<Eigen::Vector3d> x_, v_, w_, f_, t_, anchor_;
  std::vector<double> r_, invMass_, invInertia_;
  double totalMass_ = 0, rMax_ = 0, skin_ = 0, reach_ = 0, drift_ = 0, speed_ = 0;
  bool built_ = false, finite_ = true;
  GranularPairs pairs_;
  std::vector<SurfaceContact> found_;
  std::vector<SurfaceHistory> histories_, previous_;
  std::vector<std::uint32_t> surfaceStart_, previousStart_;
  GranularStats stats_;
  std::optional<GranularFailure> failure_;
  std::size_t maxPairs_ = 0;
  std::uint64_t steps_ = 0;
  double time_ = 0;
  // The energy check (checkEnergy()).
  bool measured_ = false;
  double startEnergy_ = 0, bodyWork_ = 0, potential_ = 0, elastic_ = 0, surfaceElastic_ = 0, energyFloor_ = 0;
};

}  // namespace

std::unique_ptr<GranularBody> makeGranularDem(GranularSetup setup) {
  return std::make_unique<GranularDem>(std::move(setup));
}

}  // namespace rscene::sim
