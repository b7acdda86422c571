#include "sim/granular_dem.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

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
  }

  void step(double dt, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) override {
    if (x_.empty() || !(dt > 0)) return;
    // create() chose substeps_ for the scene's time step; a caller stepping
    // longer steps gets what stability needs for them (the same rule).
    int n = substeps_;
    const double needed = std::ceil(dt / maxSubstep_ - 1e-9);
    if (needed > n) n = static_cast<int>(std::min<double>(kMaxSubsteps, needed));
    stats_.substepsPerStep = n;
    const double h = dt / n;
    for (int s = 0; s < n; ++s) substep(h, h / dt, gravity, surfaces);
    finite_ = true;
    for (std::size_t i = 0; i < x_.size() && finite_; ++i)
      finite_ = x_[i].allFinite() && v_[i].allFinite() && w_[i].allFinite();
  }

  const std::vector<Eigen::Vector3d>& positions() const override { return x_; }
  const std::vector<Eigen::Vector3d>& velocities() const override { return v_; }
  const std::vector<double>& radii() const override { return r_; }
  double totalMass() const override { return totalMass_; }
  double maxSpeed() const override { return speed_; }
  bool finite() const override { return finite_; }
  const GranularStats& stats() const override { return stats_; }

 private:
  void substep(double h, double share, const Eigen::Vector3d& gravity, SurfaceQuery& surfaces) {
    Clock::time_point t = Clock::now();
    if (!fixed_ && (!built_ || drift_ > 0.5 * skin_)) rebuild();
    stats_.neighbourSeconds += since(t);

    for (std::size_t i = 0; i < x_.size(); ++i) f_[i].setZero(), t_[i].setZero();
    stats_.maxPenetration = 0;
    pairForces(h);
    stats_.contactSeconds += since(t);

    surfaceForces(h, share, surfaces);
    stats_.surfaceSeconds += since(t);

    integrate(h, gravity);
    stats_.integrateSeconds += since(t);
    stats_.particleSubsteps += x_.size();
  }

  void rebuild() {
    pairs_.build(x_, r_, rMax_, reach_);
    anchor_ = x_;
    drift_ = 0;
    built_ = true;
    ++stats_.neighbourBuilds;
    stats_.pairs = pairs_.size();
  }

  void pairForces(double h) {
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
      GranularContactForce out = granularContactForce(m_, c, h, pairs_.history[k]);
      f_[a] += out.force;
      f_[b] -= out.force;
      t_[a] += out.torqueA;
      t_[b] += out.torqueB;
      if (c.depth > 0) ++touching, stats_.maxPenetration = std::max(stats_.maxPenetration, c.depth);
    }
    stats_.contacts = touching;
  }

  void surfaceForces(double h, double share, SurfaceQuery& surfaces) {
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
        GranularContactForce out = granularContactForce(m_, c, h, hist.springs);
        f_[i] += out.force;
        t_[i] += out.torqueA;
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
};

}  // namespace

std::unique_ptr<GranularBody> makeGranularDem(GranularSetup setup) {
  return std::make_unique<GranularDem>(std::move(setup));
}

}  // namespace rscene::sim
