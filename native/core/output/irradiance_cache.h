/// @file irradiance_cache.h
/// @brief The final gather's indirect light shared between neighbouring output points: irradiance
/// caching (Ward, Rubinstein & Clear 1988) with rotational and translational gradients (Ward &
/// Heckbert 1992) (internal; final_gather.h).
///
/// The indirect light a point's rays read is smooth wherever the surfaces it sees are far off
/// compared with how far the point moves. Each point gathered with its full rays becomes a record:
/// its position x_i, normal n_i, indirect light E_i and its gradients, and R_i, the harmonic mean of
/// its rays' hit distances. A point x of normal n may take its indirect light from the records
/// whose error measure
///     eps_i(x) = |x - x_i| / R_i + sqrt(1 - n . n_i)
/// is below the accuracy a (R_i clamped to R(x) + |x - x_i|, R(x) the point's own harmonic mean
/// distance: Krivanek, Bouatouch, Pattanaik & Zara 2006's neighbour clamping), which lie neither in
/// front of it nor behind it, as
///     E(x) = sum_i w_i [E_i + (n_i x n) . grad_r E_i + (x - x_i) . grad_t E_i] / sum_i w_i,
///     w_i = 1 / eps_i - 1 / a
/// (the weight falls to 0 at the validity bound, so no record's edge shows: Tabellion & Lamorlette
/// 2004). Which points become records is decided before anything is gathered, from geometry only
/// (positions, normals and a few probe rays' hit distances), in a fixed order: the result is the
/// same whatever the threads, and, E(x) being linear in the records' light, linear in the sources.
#pragma once

#include "common/types.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace radiosity::detail {

/// How a point's indirect light (per channel) changes about it: per unit of rotation (the axis
/// n_i x n) and per metre of translation.
struct LightGradients {
    std::array<glm::dvec3, 3> rotation{}, translation{};
    /// The change at `offset` from the point with the normal turned by `turn` (= n_i x n).
    Rgb change(const glm::dvec3& offset, const glm::dvec3& turn) const {
        Rgb out(0.0);
        for (int c = 0; c < 3; ++c)
            out[c] = glm::dot(rotation[std::size_t(c)], turn) + glm::dot(translation[std::size_t(c)], offset);
        return out;
    }
};

/// The gradients of the mean of one stratified cosine-weighted gather's samples (grid x grid rays,
/// ray i in the stratum sin^2 theta in [j, j + 1) / grid, phi in 2 pi [k, k + 1) / grid for
/// j = i % grid, k = i / grid, as the final gather casts them; Ward & Heckbert 1992, eqs. for the
/// rotational gradient and the translational gradient from the strata's boundaries) as weights on
/// the samples, which they are linear in: gradient[c] = sum over rays i of sample_i[c] x weight_i.
/// Every weight lies in the tangent plane, so it is kept in the frame the rays' azimuth is measured
/// in (x along t, where phi = 0; y along b, where phi = pi / 2).
struct GradientWeights {
    std::vector<glm::dvec2> rotation, translation;  ///< per ray
};
/// `inverse_distance`: per ray, 1 / the distance to what it hit (0: it missed, infinitely far).
GradientWeights gradient_weights(int grid, const std::vector<double>& inverse_distance);

/// Gradients summed in the tangent frame of GradientWeights, per channel.
struct PlaneGradients {
    std::array<glm::dvec2, 3> rotation{}, translation{};
    /// The same in space, for the frame (t, b).
    LightGradients in_space(const glm::dvec3& t, const glm::dvec3& b) const;
};

/// An output point as the cache sees it before anything is gathered.
struct CachePoint {
    glm::dvec3 position{0.0}, normal{0.0, 0.0, 1.0};
    double harmonic_distance = 0.0;  ///< R_i: harmonic mean of its probe rays' hit distances
    bool keep = false;               ///< gathered whatever the records around it (seams, contacts, ...)
};

/// Which points are gathered (records) and, for the others, the records they are read from.
struct CachePlan {
    std::vector<uint8_t> record;  ///< per point: gathered with its full rays
    /// Per point not a record: (record's point index, normalised weight); empty for records.
    std::vector<std::vector<std::pair<int32_t, double>>> from;
    std::size_t records() const;
};

/// The records among `points` for accuracy `a` (> 0; 0 or less: every point a record): the kept
/// points first, then the others in a fixed pseudo-random order, each a record unless the records
/// so far cover it; then each other point's weights over all the records that cover it.
CachePlan plan_cache(const std::vector<CachePoint>& points, double accuracy);

/// Ward's error measure of record `r` at point `p`, with r's harmonic distance clamped to p's plus
/// their separation (Krivanek et al. 2006's neighbour clamping), or a negative value where `r` may not
/// be read there (in front of or behind the point, or too far turned).
double cache_error(const CachePoint& r, const CachePoint& p);

/// One record's indirect light read at `p`: E_i plus its gradients' change.
Rgb read_record(const CachePoint& record, const Rgb& indirect, const LightGradients& gradients, const CachePoint& p);

}  // namespace radiosity::detail
