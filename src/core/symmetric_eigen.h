#pragma once
// Eigenvalues and eigenvectors of a small symmetric matrix by cyclic Jacobi rotations: the
// principal directions of a point set (cards of a level of detail) and the rotation that best
// maps one point set onto another (organs followed through animation frames).

#include <array>
#include <cmath>

namespace plantarch {

template <int N>
struct SymmetricEigen {
    std::array<double, N> values;
    /// vectors[i]: the unit eigenvector of values[i].
    std::array<std::array<double, N>, N> vectors;
};

/// The eigen-decomposition of the symmetric matrix `a` (a[i][j] == a[j][i]), in no particular
/// order. Rotations stop when the off-diagonal part is below 1e-30 of the diagonal's (squared
/// sums), or after 50 sweeps.
template <int N>
SymmetricEigen<N> symmetricEigen(std::array<std::array<double, N>, N> a) {
    std::array<std::array<double, N>, N> v{};  // v[k][p]: component k of eigenvector p
    for (int i = 0; i < N; ++i) v[i][i] = 1.0;
    for (int sweep = 0; sweep < 50; ++sweep) {
        double off = 0.0, diagonal = 0.0;
        for (int i = 0; i < N; ++i)
            for (int j = 0; j < N; ++j) (i == j ? diagonal : off) += a[i][j] * a[i][j];
        if (off <= 1e-30 * diagonal || off == 0.0) break;
        for (int p = 0; p < N - 1; ++p)
            for (int q = p + 1; q < N; ++q) {
                if (a[p][q] == 0.0) continue;
                const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                const double t =
                    (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
                const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                for (int k = 0; k < N; ++k) {  // a J
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                }
                for (int k = 0; k < N; ++k) {  // J^T (a J)
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for (int k = 0; k < N; ++k) {  // v J
                    const double vkp = v[k][p], vkq = v[k][q];
                    v[k][p] = c * vkp - s * vkq;
                    v[k][q] = s * vkp + c * vkq;
                }
            }
    }
    SymmetricEigen<N> out;
    for (int p = 0; p < N; ++p) {
        out.values[std::size_t(p)] = a[p][p];
        for (int k = 0; k < N; ++k) out.vectors[std::size_t(p)][std::size_t(k)] = v[k][p];
    }
    return out;
}

}  // namespace plantarch
