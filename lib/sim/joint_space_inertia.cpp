#include "sim/joint_space_inertia.hpp"

#include <algorithm>
#include <cmath>

namespace rscene::sim {

namespace {

// A body's rotational inertia about the origin, symmetric (xx yy zz xy xz
// yz): R^T diag(d) R for principal moments d in its axes (R taking world
// vectors into them), plus the parallel-axis term m (|c|^2 1 - c c^T) for
// its centre of mass c.
void inertiaAboutOrigin(const btMatrix3x3& r, const btVector3& d, btScalar m, const btVector3& c, btScalar out[6]) {
  auto rotated = [&](int i, int j) { return r[0][i] * d[0] * r[0][j] + r[1][i] * d[1] * r[1][j] + r[2][i] * d[2] * r[2][j]; };
  const btScalar cc = c.length2();
  out[0] = rotated(0, 0) + m * (cc - c.x() * c.x());
  out[1] = rotated(1, 1) + m * (cc - c.y() * c.y());
  out[2] = rotated(2, 2) + m * (cc - c.z() * c.z());
  out[3] = rotated(0, 1) - m * c.x() * c.y();
  out[4] = rotated(0, 2) - m * c.x() * c.z();
  out[5] = rotated(1, 2) - m * c.y() * c.z();
}

btVector3 times(const btScalar in[6], const btVector3& w) {
  return btVector3(in[0] * w.x() + in[3] * w.y() + in[4] * w.z(), in[3] * w.x() + in[1] * w.y() + in[5] * w.z(),
                   in[4] * w.x() + in[5] * w.y() + in[2] * w.z());
}

btScalar dot6(const btScalar* a, const btVector3& top, const btVector3& bottom) {
  return a[0] * top[0] + a[1] * top[1] + a[2] * top[2] + a[3] * bottom[0] + a[4] * bottom[1] + a[5] * bottom[2];
}

}  // namespace

bool JointSpaceInertia::sameTopology(const btMultiBody& mb) const {
  if (topology_.size() != 2 * static_cast<std::size_t>(mb.getNumLinks()) || n_ != mb.getNumDofs() + 6) return false;
  for (int i = 0; i < mb.getNumLinks(); ++i) {
    const btMultibodyLink& link = mb.getLink(i);
    if (topology_[2 * static_cast<std::size_t>(i)] != link.m_parent ||
        topology_[2 * static_cast<std::size_t>(i) + 1] != link.m_dofCount)
      return false;
  }
  return true;
}

void JointSpaceInertia::buildTopology(const btMultiBody& mb) {
  const int links = mb.getNumLinks();
  n_ = mb.getNumDofs() + 6;
  const auto n = static_cast<std::size_t>(n_);
  topology_.clear();
  std::vector<int> parent(n, -1);
  bodyOf_.assign(n, 0);
  lastOf_.assign(static_cast<std::size_t>(links) + 1, 5);
  for (int k = 1; k < 6; ++k) parent[static_cast<std::size_t>(k)] = k - 1;
  for (int i = 0; i < links; ++i) {
    const btMultibodyLink& link = mb.getLink(i);
    topology_.push_back(link.m_parent);
    topology_.push_back(link.m_dofCount);
    int last = lastOf_[static_cast<std::size_t>(link.m_parent + 1)];
    for (int d = 0; d < link.m_dofCount; ++d) {
      const auto k = static_cast<std::size_t>(6 + link.m_dofOffset + d);
      bodyOf_[k] = i + 1;
      parent[k] = last;
      last = static_cast<int>(k);
    }
    lastOf_[static_cast<std::size_t>(i) + 1] = last;
  }
  start_.assign(n + 1, 0);
  ancestors_.clear();
  work_ = 0;
  for (std::size_t k = 0; k < n; ++k) {
    for (int i = parent[k]; i >= 0; i = parent[static_cast<std::size_t>(i)]) ancestors_.push_back(i);
    start_[k + 1] = static_cast<int>(ancestors_.size());
    long row = start_[k + 1] - start_[k] + 1;
    work_ += row * row;
  }
  value_.resize(ancestors_.size());
  diagonal_.resize(n);
  inverseDiagonal_.resize(n);
  twists_.resize(6 * n);
}

bool JointSpaceInertia::factor(const btMultiBody& mb) {
  const int links = mb.getNumLinks();
  if (mb.getNumDofs() + 6 > kMaxSize) return false;
  for (int i = 0; i < links; ++i)
    if (mb.isLinkKinematic(i)) return false;
  if (!sameTopology(mb)) buildTopology(mb);
  if (work_ > kMaxWorkPerBody * (links + 1)) return false;
  fixedBase_ = mb.isBaseStaticOrKinematic();
  origin_ = mb.getBasePos();
  bodies_.resize(static_cast<std::size_t>(links) + 1);

  // Poses, the way Bullet's Jacobians walk them: each link's axes from its
  // parent's and the cached rotation, its centre of mass from its parent's
  // and the cached offset (given in the link's axes); then each body's
  // inertia about the origin.
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    Body& body = bodies_[b];
    const btVector3* local = &mb.getBaseInertia();
    if (b == 0) {
      body.rotation = mb.getWorldToBaseRot();
      body.com.setZero();
      body.mass = mb.getBaseMass();
    } else {
      const btMultibodyLink& link = mb.getLink(static_cast<int>(b) - 1);
      const Body& p = bodies_[static_cast<std::size_t>(link.m_parent + 1)];
      body.rotation = link.m_cachedRotParentToThis * p.rotation;
      body.mass = link.m_mass;
      local = &link.m_inertiaLocal;
    }
    body.fromWorld.setRotation(body.rotation);
    if (b > 0) {
      const btMultibodyLink& link = mb.getLink(static_cast<int>(b) - 1);
      body.com = bodies_[static_cast<std::size_t>(link.m_parent + 1)].com + link.m_cachedRVector * body.fromWorld;
    }
    inertiaAboutOrigin(body.fromWorld, *local, body.mass, body.com, body.inertia);
    body.moment = body.mass * body.com;
  }
  // Each subtree's inertia: a child (a higher index) is complete before it
  // is added to its parent.
  for (int i = links - 1; i >= 0; --i) {
    const Body& b = bodies_[static_cast<std::size_t>(i) + 1];
    Body& p = bodies_[static_cast<std::size_t>(mb.getLink(i).m_parent + 1)];
    p.mass += b.mass;
    p.moment += b.moment;
    for (int e = 0; e < 6; ++e) p.inertia[e] += b.inertia[e];
  }

  // Unit twists: the base's six axes, then each joint axis moved to the origin.
  std::fill(twists_.begin(), twists_.end(), btScalar(0));
  for (std::size_t k = 0; k < 6; ++k) twists_[6 * k + k] = 1;
  for (int i = 0; i < links; ++i) {
    const btMultibodyLink& link = mb.getLink(i);
    const Body& b = bodies_[static_cast<std::size_t>(i) + 1];
    for (int d = 0; d < link.m_dofCount; ++d) {
      btVector3 w = link.getAxisTop(d) * b.fromWorld;
      btVector3 v = link.getAxisBottom(d) * b.fromWorld + b.com.cross(w);
      btScalar* s = &twists_[6 * static_cast<std::size_t>(6 + link.m_dofOffset + d)];
      for (int a = 0; a < 3; ++a) s[a] = w[a], s[3 + a] = v[a];
    }
  }

  // M_kj = s_j . (I_b s_k) for j = k and its ancestors, with I_b the
  // composite inertia of k's body: the composite-rigid-body algorithm.  A
  // fixed base gets an identity block, uncoupled (its six are zeroed in
  // solve()).
  for (int k = 0; k < n_; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const int begin = start_[kk], end = start_[kk + 1];
    if (fixedBase_ && k < 6) {
      diagonal_[kk] = 1;
      std::fill(value_.begin() + begin, value_.begin() + end, btScalar(0));
      continue;
    }
    const Body& body = bodies_[static_cast<std::size_t>(bodyOf_[kk])];
    const btScalar* s = &twists_[6 * kk];
    btVector3 w(s[0], s[1], s[2]), v(s[3], s[4], s[5]);
    btVector3 fw = times(body.inertia, w) + body.moment.cross(v);
    btVector3 fv = body.mass * v - body.moment.cross(w);
    diagonal_[kk] = dot6(s, fw, fv);
    // The base's six twists are unit axes: their entries are components.
    const btScalar force[6] = {fw[0], fw[1], fw[2], fv[0], fv[1], fv[2]};
    for (int e = begin; e < end; ++e) {
      const int j = ancestors_[static_cast<std::size_t>(e)];
      value_[static_cast<std::size_t>(e)] = j >= 6    ? dot6(&twists_[6 * static_cast<std::size_t>(j)], fw, fv)
                                            : fixedBase_ ? btScalar(0)
                                                         : force[j];
    }
  }

  // M = L^T L in place, leaves first (Featherstone's LTL): only a
  // velocity's ancestors fill in, and an ancestor's row is the tail of the
  // velocity's own list.
  btScalar* value = value_.data();
  for (int k = n_ - 1; k >= 0; --k) {
    const auto kk = static_cast<std::size_t>(k);
    btScalar d = diagonal_[kk];
    if (!(d > 0) || !std::isfinite(d)) return false;
    d = std::sqrt(d);
    diagonal_[kk] = d;
    const int begin = start_[kk], end = start_[kk + 1];
    const btScalar inverse = inverseDiagonal_[kk] = btScalar(1) / d;
    for (int e = begin; e < end; ++e) value[e] *= inverse;
    for (int e = begin; e < end; ++e) {
      const int i = ancestors_[static_cast<std::size_t>(e)];
      const btScalar a = value[e];
      diagonal_[static_cast<std::size_t>(i)] -= a * a;
      // Row i is the tail of row k after i: a separate run of value_.
      btScalar* __restrict row = value + start_[static_cast<std::size_t>(i)];
      const btScalar* __restrict tail = value + e + 1;
      for (int t = 0, length = end - e - 1; t < length; ++t) row[t] -= a * tail[t];
    }
  }
  return true;
}

void JointSpaceInertia::solve(const btScalar* in, btScalar* out) const {
  solveFirstHalf(in, out);
  solveSecondHalf(out);
}

// One column of L^T y = b, leaves first: y_k, then its share taken from
// its ancestors' entries.  A zero (a velocity off a row's path) passes
// nothing on.
void JointSpaceInertia::eliminate(int k, btScalar* out) const {
  const btScalar y = out[k] *= inverseDiagonal_[static_cast<std::size_t>(k)];
  if (y == 0) return;
  for (int e = start_[static_cast<std::size_t>(k)]; e < start_[static_cast<std::size_t>(k) + 1]; ++e)
    out[ancestors_[static_cast<std::size_t>(e)]] -= value_[static_cast<std::size_t>(e)] * y;
}

void JointSpaceInertia::solveFirstHalf(const btScalar* in, btScalar* out) const {
  std::copy(in, in + n_, out);
  for (int k = n_ - 1; k >= 0; --k) eliminate(k, out);
  // A fixed base's identity block is uncoupled: its six stay out of the product.
  if (fixedBase_) std::fill(out, out + 6, btScalar(0));
}

void JointSpaceInertia::solvePathFirstHalf(int end, const btScalar* in, btScalar* out) const {
  std::fill(out, out + n_, btScalar(0));
  const int first = start_[static_cast<std::size_t>(end)], last = start_[static_cast<std::size_t>(end) + 1];
  out[end] = in[end];
  for (int e = first; e < last; ++e) out[ancestors_[static_cast<std::size_t>(e)]] = in[ancestors_[static_cast<std::size_t>(e)]];
  // The path, leaves first: `end`, then its ancestors (nearest first, so in
  // descending order); each one's own ancestors are the rest of the path.
  eliminate(end, out);
  for (int e = first; e < last; ++e) eliminate(ancestors_[static_cast<std::size_t>(e)], out);
  if (fixedBase_) std::fill(out, out + 6, btScalar(0));
}

void JointSpaceInertia::solveSecondHalf(btScalar* x) const {
  const int* start = start_.data();
  const int* ancestor = ancestors_.data();
  const btScalar* value = value_.data();
  const btScalar* inverse = inverseDiagonal_.data();
  // L x = y, root first.
  for (int k = 0; k < n_; ++k) {
    btScalar sum = x[k];
    for (int e = start[k]; e < start[k + 1]; ++e) sum -= value[e] * x[ancestor[e]];
    x[k] = sum * inverse[k];
  }
  if (fixedBase_) std::fill(x, x + 6, btScalar(0));
}

btScalar JointSpaceInertia::pathDot(int end, const btScalar* a, const btScalar* b) const {
  btScalar sum = a[end] * b[end];
  for (int e = start_[static_cast<std::size_t>(end)]; e < start_[static_cast<std::size_t>(end) + 1]; ++e) {
    const int k = ancestors_[static_cast<std::size_t>(e)];
    sum += a[k] * b[k];
  }
  return sum;
}

void JointSpaceInertia::contactJacobian(int link, const btVector3& point, const btVector3& normal,
                                        btScalar* out) const {
  std::fill(out, out + n_, btScalar(0));
  const btVector3 arm = (point - origin_).cross(normal);
  const int last = pathEnd(link);
  auto entry = [&](int k) { out[k] = dot6(&twists_[6 * static_cast<std::size_t>(k)], arm, normal); };
  entry(last);
  for (int e = start_[static_cast<std::size_t>(last)]; e < start_[static_cast<std::size_t>(last) + 1]; ++e)
    entry(ancestors_[static_cast<std::size_t>(e)]);
}

}  // namespace rscene::sim
