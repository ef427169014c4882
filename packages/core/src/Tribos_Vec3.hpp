// Tribos_Vec3.hpp: the arithmetic of points and directions in space
// (normals, contact frames, facet areas) on std::array<double, 3>, the type
// of mesh coordinates. Each is the textbook formula, evaluated in the order
// written, so that every package gets the same bits for the same vectors.
#pragma once

#include <array>
#include <cmath>

namespace Tribos {

using Vec3 = std::array<double, 3>;

inline Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }

inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The Euclidean length.
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

// a / |a|; the caller makes sure that a is not zero.
inline Vec3 normalized(const Vec3& a) {
  const double n = norm(a);
  return {a[0] / n, a[1] / n, a[2] / n};
}

}  // namespace Tribos
