// The rotation nearest to a 3×3 matrix, by Horn's quaternion method (B. K. P. Horn, "Closed-form solution
// of absolute orientation using unit quaternions", JOSA A 4(4), 1987): tr(Rᵀ M) = qᵀ N q for a symmetric
// 4×4 N built from M, so the best unit q is N's eigenvector of the largest eigenvalue. Unlike an SVD or a
// polar iteration it needs no inverse, so singular and mirrored matrices still give a rotation.
#include "dqskin/dual_quat.hpp"

#include <cmath>

namespace dqskin {
namespace {

// Cyclic Jacobi eigen-decomposition of a symmetric 4×4 matrix. On return a's diagonal holds the
// eigenvalues and column k of v the eigenvector of a[k][k]. Deterministic and accurate to rounding.
void jacobi_eigen(double a[4][4], double v[4][4]) {
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) v[i][j] = i == j ? 1.0 : 0.0;

  for (int sweep = 0; sweep < 64; ++sweep) {
    double off = 0, total = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) (i == j ? total : off) += a[i][j] * a[i][j];
    if (off <= 1e-32 * total || off == 0) return;

    for (int p = 0; p < 3; ++p) {
      for (int q = p + 1; q < 4; ++q) {
        if (a[p][q] == 0) continue;
        // Rotation in the (p, q) plane that zeroes a[p][q], the smaller of the two angles.
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 4; ++k) {  // a ← a J
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 4; ++k) {  // a ← Jᵀ a
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 4; ++k) {  // v ← v J
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
}

}  // namespace

template <typename T>
Quat<T> nearest_rotation(const Mat3<T>& m) {
  // S[a][b] = M(b, a); with GLM's column-major m[col][row] that is m[a][b].
  auto s = [&](int a, int b) { return double(m[a][b]); };
  const double xx = s(0, 0), xy = s(0, 1), xz = s(0, 2);
  const double yx = s(1, 0), yy = s(1, 1), yz = s(1, 2);
  const double zx = s(2, 0), zy = s(2, 1), zz = s(2, 2);
  // Horn's N, quaternion order (w, x, y, z).
  double n[4][4] = {
      {xx + yy + zz, yz - zy, zx - xz, xy - yx},
      {yz - zy, xx - yy - zz, xy + yx, zx + xz},
      {zx - xz, xy + yx, -xx + yy - zz, yz + zy},
      {xy - yx, zx + xz, yz + zy, -xx - yy + zz},
  };
  double v[4][4];
  jacobi_eigen(n, v);
  int best = 0;
  for (int k = 1; k < 4; ++k)
    if (n[k][k] > n[best][best]) best = k;

  double w = v[0][best], x = v[1][best], y = v[2][best], z = v[3][best];
  const double len = std::sqrt(w * w + x * x + y * y + z * z);
  const double sign = w < 0 ? -1.0 : 1.0;
  w *= sign / len, x *= sign / len, y *= sign / len, z *= sign / len;
  return Quat<T>(T(w), T(x), T(y), T(z));
}

template Quat<float> nearest_rotation(const Mat3<float>&);
template Quat<double> nearest_rotation(const Mat3<double>&);

}  // namespace dqskin
