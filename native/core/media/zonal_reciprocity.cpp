/// @file zonal_reciprocity.cpp
/// @brief transpose() and enforce_reciprocity(): symmetric exchanges with the rows' sums kept.
#include "media/zonal.h"

#include <algorithm>
#include <cmath>

namespace radiosity {

ZonalMatrix transpose(const ZonalMatrix& R) {
    const std::size_t n = R.rows(), c = R.channels;
    ZonalMatrix T;
    T.channels = R.channels;
    T.row_start.assign(n + 1, 0);
    for (int32_t y : R.col) ++T.row_start[y + 1];
    for (std::size_t x = 0; x < n; ++x) T.row_start[x + 1] += T.row_start[x];
    T.col.resize(R.col.size());
    T.val.resize(R.val.size());
    std::vector<int64_t> next(T.row_start.begin(), T.row_start.end() - 1);
    for (std::size_t y = 0; y < n; ++y)
        for (int64_t k = R.row_start[y]; k < R.row_start[y + 1]; ++k) {
            const int64_t at = next[R.col[k]]++;
            T.col[at] = static_cast<int32_t>(y);
            for (std::size_t ch = 0; ch < c; ++ch) T.val[at * c + ch] = R.val[k * c + ch];
        }
    return T;
}

namespace {

/// S = (S + S^T) / 2 with S_xy = w_x R_xy, channel `ch`, on the union of both sparsity patterns.
struct Symmetric {
    std::vector<int64_t> row_start{0};
    std::vector<int32_t> col;
    std::vector<double> val;
};

Symmetric symmetric_exchange(const ZonalMatrix& R, const ZonalMatrix& T, const std::vector<double>& w, int ch) {
    const std::size_t n = R.rows(), c = R.channels;
    Symmetric S;
    S.row_start.reserve(n + 1);
    for (std::size_t x = 0; x < n; ++x) {
        int64_t a = R.row_start[x], b = T.row_start[x];
        const int64_t a_end = R.row_start[x + 1], b_end = T.row_start[x + 1];
        while (a < a_end || b < b_end) {
            const int32_t ya = a < a_end ? R.col[a] : INT32_MAX, yb = b < b_end ? T.col[b] : INT32_MAX;
            const int32_t y = std::min(ya, yb);
            double sum = 0.0;
            if (ya == y) sum += w[x] * R.val[a++ * c + ch];  // w_x R_xy
            if (yb == y) sum += w[y] * T.val[b++ * c + ch];  // w_y R_yx
            S.col.push_back(y);
            S.val.push_back(0.5 * sum);
        }
        S.row_start.push_back(static_cast<int64_t>(S.col.size()));
    }
    return S;
}

/// d with d_x sum_y S_xy d_y = target_x (Knight 2008: d <- d sqrt(target / row sum), all at once).
std::vector<double> symmetric_scaling(const Symmetric& S, const std::vector<double>& target) {
    const std::size_t n = target.size();
    std::vector<double> d(n, 1.0), next(n);
    for (int iteration = 0; iteration < 1000; ++iteration) {
        double worst = 0.0;
        for (std::size_t x = 0; x < n; ++x) {
            next[x] = d[x];
            if (!(target[x] > 0.0)) continue;
            double row = 0.0;
            for (int64_t k = S.row_start[x]; k < S.row_start[x + 1]; ++k) row += S.val[k] * d[S.col[k]];
            row *= d[x];
            if (!(row > 0.0)) continue;
            worst = std::max(worst, std::abs(row / target[x] - 1.0));
            next[x] = d[x] * std::sqrt(target[x] / row);
        }
        if (worst < 1e-9) break;
        d.swap(next);
    }
    return d;
}

}  // namespace

void enforce_reciprocity(ZonalMatrix& R, const std::vector<Rgb>& w) {
    if (w.size() != R.rows()) throw InputError("enforce_reciprocity: one weight per row");
    const std::size_t n = R.rows(), c = R.channels;
    const ZonalMatrix T = transpose(R);
    std::vector<Symmetric> S(c);
    std::vector<std::vector<double>> d(c);
    std::vector<std::vector<double>> weight(c, std::vector<double>(n));
    for (std::size_t ch = 0; ch < c; ++ch) {
        for (std::size_t x = 0; x < n; ++x) weight[ch][x] = w[x][ch];
        std::vector<double> target(n, 0.0);
        for (std::size_t x = 0; x < n; ++x)
            for (int64_t k = R.row_start[x]; k < R.row_start[x + 1]; ++k)
                target[x] += weight[ch][x] * R.val[k * c + ch];
        S[ch] = symmetric_exchange(R, T, weight[ch], static_cast<int>(ch));
        d[ch] = symmetric_scaling(S[ch], target);
    }
    // Every channel shares the union pattern (it only depends on R's pattern).
    ZonalMatrix out;
    out.channels = R.channels;
    out.row_start = S[0].row_start;
    out.col = S[0].col;
    out.val.resize(out.col.size() * c);
    for (std::size_t x = 0; x < n; ++x)
        for (int64_t k = out.row_start[x]; k < out.row_start[x + 1]; ++k) {
            for (std::size_t ch = 0; ch < c; ++ch) {
                const double w_x = weight[ch][x];
                out.val[k * c + ch] = w_x > 0.0 ? float(d[ch][x] * S[ch].val[k] * d[ch][out.col[k]] / w_x) : 0.0f;
            }
        }
    // Zero-weight rows (a zone channel without extinction) carry no power: keep what was measured.
    for (std::size_t x = 0; x < n; ++x)
        for (std::size_t ch = 0; ch < c; ++ch) {
            if (weight[ch][x] > 0.0) continue;
            int64_t o = out.row_start[x];
            for (int64_t k = R.row_start[x]; k < R.row_start[x + 1]; ++k) {
                while (out.col[o] != R.col[k]) ++o;
                out.val[o * c + ch] = R.val[k * c + ch];
            }
        }
    R = std::move(out);
}

}  // namespace radiosity
