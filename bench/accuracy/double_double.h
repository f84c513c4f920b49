// Double-double numbers (about 106 significant bits) for the error oracle:
// a value is hi + lo with |lo| <= ulp(hi) / 2. Algorithms from Dekker (1971),
// Knuth's TwoSum, and Hida, Li & Bailey, "Library for Double-Double and
// Quad-Double Arithmetic" (QD, 2007): sum and product of doubles are exact
// (two_sum, two_product via fma); +, -, * carry a relative error of a few
// 2^-104, / and sqrt a few 2^-103. Needs -ffp-contract=off (set project-wide)
// and no fast-math. Range: as double; no special handling of Inf or NaN.
#pragma once

#include <cmath>

namespace quiver::accuracy {

struct DoubleDouble {
  double hi = 0.0, lo = 0.0;

  DoubleDouble() = default;
  DoubleDouble(double value) : hi(value), lo(0.0) {}  // NOLINT: implicit on purpose
  DoubleDouble(double high, double low) : hi(high), lo(low) {}

  double to_double() const { return hi + lo; }
};

// s + e == a + b exactly (Knuth).
inline DoubleDouble two_sum(double a, double b) {
  const double s = a + b;
  const double b_virtual = s - a;
  const double e = (a - (s - b_virtual)) + (b - b_virtual);
  return {s, e};
}

// s + e == a + b exactly when |a| >= |b| (Dekker).
inline DoubleDouble quick_two_sum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}

// p + e == a * b exactly (the fma gives the product's rounding error).
inline DoubleDouble two_product(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}

inline DoubleDouble operator-(const DoubleDouble& a) { return {-a.hi, -a.lo}; }

inline DoubleDouble operator+(const DoubleDouble& a, const DoubleDouble& b) {
  // Both parts summed exactly, then renormalised twice (QD's accurate add).
  DoubleDouble s = two_sum(a.hi, b.hi);
  const DoubleDouble t = two_sum(a.lo, b.lo);
  s.lo += t.hi;
  s = quick_two_sum(s.hi, s.lo);
  s.lo += t.lo;
  return quick_two_sum(s.hi, s.lo);
}

inline DoubleDouble operator-(const DoubleDouble& a, const DoubleDouble& b) { return a + (-b); }

inline DoubleDouble operator*(const DoubleDouble& a, const DoubleDouble& b) {
  DoubleDouble p = two_product(a.hi, b.hi);
  p.lo += a.hi * b.lo + a.lo * b.hi;  // cross terms; lo * lo is below the precision
  return quick_two_sum(p.hi, p.lo);
}

inline DoubleDouble operator/(const DoubleDouble& a, const DoubleDouble& b) {
  // Long division: three quotient digits, each from the remainder so far.
  const double q1 = a.hi / b.hi;
  DoubleDouble r = a - b * DoubleDouble(q1);
  const double q2 = r.hi / b.hi;
  r = r - b * DoubleDouble(q2);
  const double q3 = r.hi / b.hi;
  return quick_two_sum(q1, q2) + DoubleDouble(q3);
}

// sqrt(a) for a >= 0: the double root plus one Newton step in double-double.
inline DoubleDouble sqrt(const DoubleDouble& a) {
  if (a.hi <= 0.0) return DoubleDouble(0.0);
  const double x = std::sqrt(a.hi);
  const DoubleDouble residual = a - two_product(x, x);
  return two_sum(x, residual.hi / (2.0 * x));
}

inline bool operator<(const DoubleDouble& a, const DoubleDouble& b) {
  return a.hi < b.hi || (a.hi == b.hi && a.lo < b.lo);
}
inline bool operator>(const DoubleDouble& a, const DoubleDouble& b) { return b < a; }
inline bool operator<=(const DoubleDouble& a, const DoubleDouble& b) { return !(b < a); }
inline bool operator>=(const DoubleDouble& a, const DoubleDouble& b) { return !(a < b); }
inline bool operator==(const DoubleDouble& a, const DoubleDouble& b) { return a.hi == b.hi && a.lo == b.lo; }

inline DoubleDouble abs(const DoubleDouble& a) { return a.hi < 0.0 || (a.hi == 0.0 && a.lo < 0.0) ? -a : a; }

// Vectors of double-double numbers for the oracle's geometry.
struct DDVec3 {
  DoubleDouble x, y, z;
};

inline DDVec3 operator+(const DDVec3& a, const DDVec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline DDVec3 operator-(const DDVec3& a, const DDVec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline DDVec3 operator*(const DDVec3& a, const DoubleDouble& s) { return {a.x * s, a.y * s, a.z * s}; }
inline DoubleDouble dot(const DDVec3& a, const DDVec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline DDVec3 cross(const DDVec3& a, const DDVec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

}  // namespace quiver::accuracy
