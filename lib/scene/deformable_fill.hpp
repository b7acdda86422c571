// RaiSim's "Filled" particle mode and its internal struts: particles on a
// regular grid inside a closed triangle mesh, and distance constraints
// between particles close to each other.  Both bound their work and their
// memory and refuse (false with a sentence) past the bounds.
#pragma once
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace rscene {

// True when every edge of the triangles is shared by exactly two of them
// (a closed surface); else `error` names an open or non-manifold edge.
bool closedSurface(const std::vector<std::array<std::uint32_t, 3>>& triangles, std::string& error);

// Appends to `out` the grid points at `spacing` inside the closed surface
// (vertices in any frame; the grid is aligned with its axes and centred in
// its bounds), leaving out points within spacing/4 of the surface along
// the grid's z rays.  Refuses when the result would make more than
// `maxTotal` particles with out's existing ones (counted before anything
// is appended) or the search would take more than a bounded work.
bool fillClosedSurface(const std::vector<Eigen::Vector3d>& vertices,
                       const std::vector<std::array<std::uint32_t, 3>>& triangles, double spacing,
                       std::uint64_t maxTotal, std::vector<Eigen::Vector3d>& out, std::string& error);

// Pairs (i < j, in increasing order) of points no further than `radius`
// apart; refuses past `maxPairs` pairs or a bounded work.
bool pairsWithinRadius(const std::vector<Eigen::Vector3d>& points, double radius, std::uint64_t maxPairs,
                       std::vector<std::pair<std::uint32_t, std::uint32_t>>& out, std::string& error);

}  // namespace rscene
