/// @file links.cpp
/// @brief Factor and error estimates of node pairs, and link refinement (hierarchy.h).
#include "hierarchy/links.h"

#include "common/parallel_rows.h"
#include "common/report_progress.h"
#include "transport/near_field.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <tuple>
#include <utility>

namespace radiosity::hr {
namespace {

uint32_t mix(uint32_t h) {  // a small integer hash (for spreading cluster samples)
    h ^= h >> 16;
    h *= 0x7feb352dU;
    h ^= h >> 15;
    h *= 0x846ca68bU;
    h ^= h >> 16;
    return h;
}

/// Samples of a transfer: their mean and largest value.
struct Samples {
    double high = 0.0, sum = 0.0;
    int count = 0;
    void add(double v) {
        high = std::max(high, v);
        sum += v;
        ++count;
    }
    double mean() const { return count ? sum / count : 0.0; }
};

/// How a transfer sampled at an element's probes (element_probes: inset corners, then the
/// centre) varies over it: its whole spread, and its departure from linear (the centre against
/// the corners' mean, and a quad's twist), which is all a leaf's interpolated corners miss.
struct Variation {
    double spread = 0.0, nonlinear = 0.0;
};

Variation variation(const double* at, int probe_count) {
    Variation v;
    const auto [low, high] = std::minmax_element(at, at + probe_count);
    v.spread = *high - *low;
    const int corners = probe_count - 1;
    double mean = 0.0;
    for (int k = 0; k < corners; ++k) mean += at[k] / corners;
    v.nonlinear = 2.0 * std::abs(at[corners] - mean);
    if (corners == 4) v.nonlinear += std::abs(at[0] - at[1] + at[2] - at[3]);
    v.nonlinear = std::min(v.nonlinear, v.spread);
    return v;
}

/// A seed from a pair's geometry, not from node ids (which depend on the order threads made
/// the nodes in): the same scene traces the same rays every run.
uint32_t pair_seed(const Node& r, const Node& s) {
    uint32_t h = 0x811c9dc5U;
    for (const Node* n : {&r, &s})
        for (float x : {n->centre.x, n->centre.y, n->centre.z, n->area, n->radius}) {
            uint32_t bits;
            std::memcpy(&bits, &x, sizeof bits);
            h = mix(h ^ bits);
        }
    return h;
}

/// The fractions of the segment a - b where it enters and leaves node n's bounding sphere
/// (entry < 0: a is inside); {1, 1} when it misses the sphere.
std::pair<float, float> sphere_span(const Vec3& a, const Vec3& b, const Node& n) {
    const glm::dvec3 d(b - a), m(a - n.centre);
    const double dd = glm::dot(d, d), md = glm::dot(m, d);
    const double discriminant = md * md - dd * (glm::dot(m, m) - double(n.radius) * double(n.radius));
    if (!(dd > 0.0) || discriminant < 0.0) return {1.0f, 1.0f};
    const double root = std::sqrt(discriminant);
    return {float((-md - root) / dd), float(std::clamp((-md + root) / dd, 0.0, 1.0))};
}

/// Estimates one task makes before it hands its remaining pairs on (some 10 ms).
constexpr int kEstimatesPerTask = 4096;

/// Links placed in their receivers' lists between two progress reports (some 0.1 s).
constexpr std::size_t kLinksPerReport = std::size_t(1) << 20;

}  // namespace

/// Rays per cluster for its openness: its binomial doubt is at most 1 / (2 sqrt(64)) = 6%.
constexpr int kOpennessRays = 64;
/// Clusters less open than this are never a link's end (estimate_point_source).
constexpr float kOpenEnough = 0.9f;

void Refiner::measure_openness(const ProgressFn& progress) {
    openness_.assign(tree_.cluster_count, 1.0f);
    const auto patches = static_cast<int32_t>(tree_.patch_count);
    // Phase "links", with progress and cancel: at 10^6 patches these are 6.4e7 rays.
    detail::parallel_rows("links", tree_.cluster_count, 64, 0, progress, [&](std::size_t k) {
        const Node& c = tree_.nodes[tree_.patch_count + k];
        uint32_t seed = pair_seed(c, c);
        int open = 0;
        for (int ray = 0; ray < kOpennessRays; ++ray) {
            // A patch picked by area (as cluster_samples walks), a point on it, a cos-weighted
            // direction out of its front, and the ray to where it leaves the cluster's sphere.
            int32_t n = patches + int32_t(k);
            for (seed = mix(seed + 0x9e3779b9U); n >= patches; seed = mix(seed)) {
                const ClusterSplit& split = tree_.splits[n - patches];
                n = split.child[seed / 4294967296.0 < split.area_share ? 0 : 1];
            }
            const Node& patch = tree_.nodes[n];
            Vec3 from;
            jittered_points(tree_, patch, 1, seed, &from);
            seed = mix(seed);
            const float u1 = float(seed >> 8) / 16777216.0f;
            seed = mix(seed);
            const float phi = 2.0f * float(M_PI) * float(seed >> 8) / 16777216.0f;
            const Vec3 normal = patch.normal;
            const Vec3 t =
                glm::normalize(glm::cross(std::abs(normal.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0), normal));
            const Vec3 b = glm::cross(normal, t);
            const float radial = std::sqrt(u1);
            const Vec3 direction =
                radial * std::cos(phi) * t + radial * std::sin(phi) * b + std::sqrt(1.0f - u1) * normal;
            const glm::dvec3 m(from - c.centre), d(direction);
            const double half = glm::dot(m, d), rest = glm::dot(m, m) - double(c.radius) * c.radius;
            const double length = -half + std::sqrt(std::max(0.0, half * half - rest));
            open += !(length > 0.0) || visibility_.clear(from, from + float(length) * direction);
        }
        openness_[k] = float(open) / kOpennessRays;
        return true;
    });
}

Refiner::Estimate Refiner::must_split(bool source_side) {
    Estimate e;
    e.useful = true;
    e.source_side = source_side;
    e.link.uncertainty = std::numeric_limits<float>::max();
    return e;
}

bool Refiner::is_must_split(const Link& link) { return link.uncertainty == std::numeric_limits<float>::max(); }

Rgb intensity(const Tree& tree, const Node& source, const Vec3& u) {
    switch (source.kind) {
        case Kind::PointLamp:
            return tree.lights.points[source.lamp].intensity;  // profile: in the factor
        case Kind::Sun:
            return tree.lights.suns[source.lamp].irradiance;
        default:
            break;
    }
    const glm::dvec3 direction(u);
    auto towards = [&](const Emitter& emitter) {
        Rgb out;
        for (int c = 0; c < 3; ++c) {
            const glm::dvec3& m = emitter.moment[c];
            out[c] = std::max(0.0, glm::dot(m, direction)) +
                     std::max(0.0, emitter.power[c] - emitter.moment_length[c]) / 4.0;
        }
        return out;
    };
    return source.kind == Kind::Cluster ? towards(tree.emitters[source.cluster]) : towards(element_emitter(source));
}

int Refiner::cluster_samples(const Node& c, uint32_t seed, bool by_power, std::array<Vec3, 4>& points) const {
    // Each point is a patch centre reached by walking down from c, taking each child with odds
    // proportional to its power (where the light comes from) or its area (where it lands).
    // Clusters are the nodes after the patches, and a cluster's children are clusters or patches.
    const auto patches = static_cast<int32_t>(tree_.patch_count);
    for (int k = 0; k < 4; ++k) {
        int32_t n = patches + c.cluster;
        for (uint32_t h = mix(seed + 0x9e3779b9U * (k + 1)); n >= patches; h = mix(h)) {
            const ClusterSplit& split = tree_.splits[n - patches];
            n = split.child[h / 4294967296.0 < (by_power ? split.power_share : split.area_share) ? 0 : 1];
        }
        points[k] = tree_.patch_centres[n];
    }
    return 4;
}

Refiner::Estimate Refiner::estimate(int32_t receiver, int32_t source) const {
    const Node& r = tree_.nodes[receiver];
    const Node& s = tree_.nodes[source];
    Estimate e = r.is_element() && s.is_element() ? estimate_elements(r, s) : estimate_point_source(r, s);
    e.link.source = source;
    return e;
}

Refiner::Estimate Refiner::estimate_elements(const Node& r, const Node& s) const {
    Estimate e;
    std::array<Vec3, 4> P, C;
    const int np = element_samples(tree_, r, P);
    const int nc = element_corners(tree_, s, C);
    glm::dvec3 polygon[4];
    for (int k = 0; k < nc; ++k) polygon[k] = C[k];
    // A point in s's plane (within the gap rays leave at their ends) sees none of s. Lambert's
    // formula, from a point inside a coplanar polygon that rounding puts a hair in front of it,
    // gives the whole hemisphere: an emitter's two sides (Elements::side), back to back, would
    // light each other fully.
    const float in_plane = 1e-6f * tree_.scene_size;
    auto factor_at = [&](const Vec3& x) {
        if (!(glm::dot(s.normal, x - s.centre) > in_plane) || in_plane_of(tree_, s, x, r.normal)) return 0.0;
        return point_to_polygon(glm::dvec3(x), glm::dvec3(r.normal), polygon, nc, glm::dvec3(s.normal));
    };
    Samples F;  // over r's Gauss points
    for (int k = 0; k < np; ++k) F.add(factor_at(P[k]));
    std::array<Vec3, 5> probes;
    std::array<double, 5> at{};
    const int probe_count = element_probes(tree_, r, probes);
    for (int k = 0; k < probe_count; ++k) at[k] = factor_at(probes[k]);
    if (!(F.high > 0.0) && !(*std::max_element(at.begin(), at.begin() + probe_count) > 0.0))
        return e;  // s is behind r, or r behind s: no light either way

    // Visibility from jittered points, so that a fraction errs at random, not the same way on
    // every link (fixed points would see the same gap or the same occluder every time).
    const uint32_t seed = pair_seed(r, s);
    std::array<Vec3, 16> from, to;
    // Each ray counts with the kernel cos cos / d^2 of its ends, so that parts of s behind r's
    // plane (or of r behind s's) neither hide nor show anything.
    auto visible_fraction = [&](int rays, int stride, bool& partial) {
        double seen = 0.0, total = 0.0;
        int hits = 0, misses = 0;
        for (int k = 0; k < rays; ++k) {
            const Vec3 &a = from[k], &b = to[(stride * k + 1) % rays];
            const double kernel = pair_kernel(r.normal, s.normal, b - a);
            if (!(kernel > 0.0)) continue;
            const bool clear = visibility_.clear(a, b);
            (clear ? hits : misses) += 1;
            seen += clear ? kernel : 0.0;
            total += kernel;
        }
        partial = hits > 0 && misses > 0;
        return total > 0.0 ? seen / total : 1.0;  // no ray found the front: F is near 0 anyway
    };
    // Coarse receivers get 16 rays (a small occluder hides among 4), the finest 4, or 16 when
    // those disagree.
    const int grid = tree_.can_split(r) ? 4 : 2;
    jittered_points(tree_, r, grid, seed, from.data());
    jittered_points(tree_, s, grid, mix(seed), to.data());
    bool partial = false;
    int rays = grid * grid;
    double visible = visible_fraction(rays, grid == 4 ? 5 : 1, partial);
    // A partly hidden source over a receiver that can split: split the receiver, to find the
    // shadow's edge on it. Over one that cannot: 16 rays for a finer fraction, whose remaining
    // doubt (two binomial deviations) may still ask to split the source.
    double hidden_doubt = partial ? 1.0 : 0.0;
    if (partial && !tree_.can_split(r)) {
        jittered_points(tree_, r, 4, mix(seed + 1), from.data());
        jittered_points(tree_, s, 4, mix(seed + 2), to.data());
        rays = 16;
        visible = visible_fraction(rays, 5, partial);
        hidden_doubt = 2.0 * std::sqrt(visible * (1.0 - visible) / rays);
    }
    e.rays = rays;
    e.link.factor = static_cast<float>(F.mean() * visible);
    // Only error that splitting can still reduce counts: how the factor varies over a receiver
    // too small to split stays; a partly hidden source can still be split to find the shadow.
    const double rho = max_channel(r.reflectance);
    const Variation v = tree_.can_split(r) ? variation(at.data(), probe_count) : Variation{};
    e.link.uncertainty = static_cast<float>(rho * (v.nonlinear + hidden_doubt * F.mean()));
    e.link.steps = static_cast<float>(rho * (v.spread - v.nonlinear));
    // Where s is partly hidden or large and near, which of its parts r sees matters: the mean
    // radiance errs by up to the spread of s's radiance (the floor under a block is dark, the
    // part in view is not). Four rays can miss an occluder, so nearness counts too (its cube:
    // measured on the Cornell box, the best accuracy for the links among 1, 2 and 3 powers).
    const double distance = glm::length(s.centre - r.centre);
    const double near = distance > 0.0 ? std::min(1.0, 2.0 * s.radius / distance) : 1.0;
    if (tree_.can_split(s))
        e.link.source_doubt =
            static_cast<float>(max_channel(r.reflectance) * F.mean() * (partial ? 1.0 : near * near * near));
    e.useful = e.link.factor > 0.0f || e.link.uncertainty > 0.0f || e.link.source_doubt > 0.0f || e.link.steps > 0.0f;
    return e;
}

Refiner::Estimate Refiner::estimate_point_source(const Node& r, const Node& s) const {
    Estimate e;
    const bool sun = s.kind == Kind::Sun;
    if (s.is_lamp() && r.kind == Kind::Cluster) {
        // A lamp's light reaches each patch on its own link: a cluster's few sample rays would
        // miss most shadows in it, and its children would all get the same light.
        return must_split();
    }
    const uint32_t seed = pair_seed(r, s);
    std::array<Vec3, 4> P, Q;
    const int np = r.is_element() ? element_samples(tree_, r, P) : cluster_samples(r, seed, false, P);
    int nq = 1;
    if (s.kind == Kind::Cluster)
        nq = cluster_samples(s, seed ^ 0x5bd1e995U, true, Q);
    else if (s.kind == Kind::Element)
        nq = element_samples(tree_, s, Q);
    else
        Q[0] = s.centre;

    const PointLight* lamp = s.kind == Kind::PointLamp ? &tree_.lights.points[s.lamp] : nullptr;
    auto transfer = [&](const Vec3& x, const Vec3& q) {  // per unit of the source's intensity, x from q
        const Vec3 d = sun ? -s.normal : q - x;
        const double distance2 = sun ? 1.0 : glm::dot(d, d);
        if (!(distance2 > 0.0)) return std::numeric_limits<double>::infinity();
        const Vec3 u = sun ? d : d / std::sqrt(float(distance2));
        double value = (r.is_element() ? std::max(0.0f, glm::dot(r.normal, u)) : 1.0) / (M_PI * distance2);
        if (lamp) value *= spot_profile(*lamp, -u);
        if (s.is_element()) value *= glm::dot(s.normal, -u) > 0.0f ? 1.0 : 0.0;  // an element lights its front
        return value;
    };
    auto transfer_at = [&](const Vec3& x) { return transfer(x, s.centre); };
    // The mean over pairs of points of both ends: 1 / d^2 averaged over an extended source (or
    // receiver) exceeds its value at the centres, which would lose light all over the scene.
    Samples g;
    for (int k = 0; k < np; ++k) {
        double sum = 0.0;
        for (int j = 0; j < nq; ++j) sum += transfer(P[k], Q[j]);
        g.add(sum / nq);
    }
    std::array<double, 5> at{};
    int probe_count = 0;
    if (r.is_element()) {
        std::array<Vec3, 5> probes;
        probe_count = element_probes(tree_, r, probes);
        for (int k = 0; k < probe_count; ++k) at[k] = transfer_at(probes[k]);
    }
    const double highest =
        std::max(g.high, probe_count ? *std::max_element(at.begin(), at.begin() + probe_count) : 0.0);
    if (!std::isfinite(highest)) {  // a point source on the receiver: split, or no link
        return must_split();
    }
    if (!(highest > 0.0)) {
        // A cluster's few sample points may all lie where the element at the other end cannot
        // see them (a block face and the floor under the block, against the floor strip in front)
        // while some of its parts can: split the pair rather than lose that light.
        auto reaches_front = [](const Node& element, const Node& cluster) {
            return glm::dot(element.normal, cluster.centre - element.centre) > -cluster.radius;
        };
        const bool may_reach = (s.kind == Kind::Cluster && r.is_element() && reaches_front(r, s)) ||
                               (r.kind == Kind::Cluster && s.is_element() && reaches_front(s, r));
        return may_reach ? must_split(s.kind == Kind::Cluster) : e;
    }

    // A cluster end whose parts hide a tenth of it or more from what lies outside (blocks on a
    // floor) is no point source nor an ambient cube: its parts are linked instead. Measured on a
    // closed 2 m room with 200 blocks on its floor: 100.8% of the emitted light absorbed with the
    // doubt below alone (refinement ran out of rounds), 99.97% with this, and fewer links.
    if (openness(r) < kOpenEnough) return must_split(false);
    if (openness(s) < kOpenEnough) return must_split(true);
    // Coarse element receivers get rays from jittered points: 16, or for a lamp one per cell of
    // about 4 minimum element sizes (up to 16 x 16), since its light may be even over the whole
    // receiver and nothing but these rays would find a small shadow on it.
    std::vector<Vec3> from(P.begin(), P.begin() + np);
    if (r.is_element() && tree_.can_split(r)) {
        const bool lamp_source = s.is_lamp();
        const int grid =
            lamp_source ? std::clamp(int(std::ceil(r.longest_edge / (4.0f * tree_.min_element_size()))), 4, 16) : 4;
        from.resize(std::size_t(grid) * grid);
        jittered_points(tree_, r, grid, seed, from.data());
    }
    const int from_count = static_cast<int>(from.size());
    const int rays = std::max(from_count, nq);
    int clear = 0;
    for (int k = 0; k < rays; ++k) {
        const Vec3& a = from[k % from_count];
        if (sun) {
            clear += visibility_.clear_towards(a, -s.normal);
            continue;
        }
        // A cluster's own surfaces hiding its other parts are in its intensity (sources) or its
        // ambient cube (receivers), not in the visibility between the two: rays count only
        // occluders between the clusters' bounding spheres.
        const Vec3& q = Q[(k + 1) % nq];
        const float begin = r.kind == Kind::Cluster ? sphere_span(a, q, r).second : 0.0f;
        const float end = s.kind == Kind::Cluster ? sphere_span(a, q, s).first : 1.0f;
        clear += visibility_.clear(a, q, begin, end < 0.0f ? 1.0f : end);
    }
    e.rays = rays;
    const double visible = double(clear) / rays;
    const bool partial = clear > 0 && clear < rays;
    // Treating both ends as points is off by about their size over the distance between them;
    // closer than twice their size, the points say nothing: such pairs must split.
    const double distance = sun ? std::numeric_limits<double>::infinity() : glm::length(s.centre - r.centre);
    auto extent = [](const Node& n) { return n.kind == Kind::Cluster || n.is_element() ? double(n.radius) : 0.0; };
    const double r_extent = r.is_element() ? 0.0 : extent(r), s_extent = extent(s);
    if (distance < 2.0 * (r_extent + s_extent)) return must_split(s_extent >= r_extent && s_extent > 0.0);
    const Variation v = probe_count && tree_.can_split(r) ? variation(at.data(), probe_count) : Variation{};
    e.link.steps = static_cast<float>(max_channel(r.reflectance) * (v.spread - v.nonlinear));
    // A cluster end that is not open (Refiner::openness) makes light from nothing in that share.
    const double receiver_part =
        v.nonlinear + g.mean() * (2.0 * r_extent / distance + (partial ? 1.0 : 0.0) + (1.0 - openness(r)));
    const double source_part = g.mean() * (2.0 * s_extent / distance + (1.0 - openness(s)));
    e.source_side = source_part > receiver_part;
    e.link.factor = static_cast<float>(g.mean() * visible);
    e.link.uncertainty = static_cast<float>(max_channel(r.reflectance) * (receiver_part + source_part));
    e.useful = true;
    return e;
}

double Refiner::source_error(const Link& link) const {
    const Node& s = tree_.nodes[link.source];
    return double(link.source_doubt) * double(s.radiance_high - s.radiance_low);
}

double Refiner::error(const Node& receiver, const Link& link, bool receiver_split) const {
    const Node& s = tree_.nodes[link.source];
    const double doubt = double(link.uncertainty) + (receiver_split ? double(link.steps) : 0.0);
    if (receiver.is_element() && s.is_element()) return doubt * max_channel(s.radiance) + source_error(link);
    // Intensity towards the centre direction is itself an estimate (other parts of the receiver
    // see the source from elsewhere): bound the error by at least a quarter of the source's power,
    // its mean intensity over all directions.
    double strength = max_channel(intensity(tree_, s, -towards_source(receiver, s)));
    if (s.kind == Kind::Cluster || s.is_element()) strength = std::max(strength, max_channel(tree_.power(s)) / 4.0);
    return doubt * strength;
}

double Refiner::receiver_threshold(const Node& receiver, double threshold) const {
    // A receiver smaller than an element of the minimum size may err by as much light in total
    // (radiance times area) as such an element: Hanrahan et al.'s BFA below the scale the bake was
    // asked to resolve. Measured on the Cornell box and the shadow room: the same RMS error to
    // three digits with a sixth to a third fewer links (docs/hierarchy.md).
    const double element_area = double(tree_.min_element_size()) * tree_.min_element_size();
    return receiver.area > 0.0f && receiver.area < element_area ? threshold * element_area / receiver.area : threshold;
}

void Refiner::link_depth_first(const Pending& pair, double threshold, Output& out, std::vector<Pending>& next,
                               std::size_t& rays) {
    std::vector<Pending> stack{pair};
    for (int estimates = 0; !stack.empty(); ++estimates) {
        if (estimates == kEstimatesPerTask) {
            next.insert(next.end(), stack.begin(), stack.end());
            return;
        }
        const Pending top = stack.back();
        stack.pop_back();
        link(top, threshold, out, stack, rays);
    }
}

void Refiner::link(const Pending& pair, double threshold, Output& out, std::vector<Pending>& stack, std::size_t& rays) {
    const auto [receiver, source, split] = pair;
    --links_;  // the pair held a place in links_ while it waited
    const Estimate e = estimate(receiver, source);
    rays += e.rays;
    const Node& r = tree_.nodes[receiver];
    const Node& s = tree_.nodes[source];
    // A factor that is not a number would spread through every sweep: an error here, naming the
    // receiver's polygon (or the source's, for a cluster receiver).
    if (!std::isfinite(e.link.factor) || std::isnan(e.link.uncertainty))
        throw NumericalError("links", r.is_element() ? input_polygon(tree_, r) : input_polygon(tree_, s));
    if (!e.useful) return;
    // Pairs too close for their estimate split whatever the threshold (even before the first
    // solve, when every source but the lamps and emitters is still dark).
    const bool too_near = is_must_split(e.link);
    const double link_error = too_near ? 0.0 : error(r, e.link, split_at_start(receiver));
    if ((split || too_near || link_error > receiver_threshold(r, threshold)) && within_memory()) {
        // Split the end the error comes from (an element's factor towards a polygon is exact over
        // the source, so only the receiver's side errs); the other end only if that one cannot.
        const bool r_splits = r.kind == Kind::Cluster || tree_.can_split(r);
        const bool s_splits = s.kind == Kind::Cluster || tree_.can_split(s);
        const bool source_side = e.source_side || source_error(e.link) > link_error - source_error(e.link);
        const bool source_first = source_side || !r_splits;
        for (const bool split_source : {source_first, !source_first}) {
            if (split_source && s_splits && (s.kind == Kind::Cluster || tree_.subdivide(source))) {
                links_ += s.child_count;
                for (int k = s.child_count; k-- > 0;) stack.push_back({receiver, child(s, k), false});
                return;
            }
            if (!split_source && r_splits && (r.kind == Kind::Cluster || tree_.subdivide(receiver))) {
                links_ += r.child_count;
                for (int k = r.child_count; k-- > 0;) stack.push_back({child(r, k), source, false});
                return;
            }
        }
    }
    out.emplace_back(receiver, e.link);
    ++links_;
}

std::size_t Refiner::bytes() const {
    const std::size_t per_cluster = sizeof(Emitter) + sizeof(AmbientCube) + sizeof(ClusterSplit);
    return tree_.nodes.size() * sizeof(Node) + tree_.cluster_count * per_cluster + links_ * sizeof(Link) +
           (tree_.vertices.size() + tree_.patch_count) * sizeof(Vec3);
}

bool Refiner::within_memory() {
    if (max_bytes_ == 0 || bytes() < max_bytes_) return true;
    memory_cap_reached_ = true;
    return false;
}

void Refiner::link_all(std::vector<Pending> pending, double threshold, const ProgressFn& progress) {
    const std::size_t first_new = tree_.nodes.size();
    tbb::enumerable_thread_specific<Output> outputs;
    tbb::enumerable_thread_specific<std::size_t> rays(0);
    links_ += pending.size();  // each waiting pair may become a link: the memory cap counts it
    std::size_t done = 0;      // pairs of the levels before: the bar counts pairs over all levels
    ProgressFn level_progress;
    if (progress)
        level_progress = [&](const Progress& p) {
            Progress all = p;
            all.done = done + p.done;
            all.total = done + p.total;
            return progress(all);
        };
    while (!pending.empty()) {
        tbb::enumerable_thread_specific<std::vector<Pending>> next;
        detail::parallel_rows("links", pending.size(), 16, 0, level_progress, [&](std::size_t i) {
            link_depth_first(pending[i], threshold, outputs.local(), next.local(), rays.local());
            return true;
        });
        done += pending.size();
        pending.clear();
        for (const auto& level : next) pending.insert(pending.end(), level.begin(), level.end());
    }
    const std::vector<int32_t> new_id = tree_.number_in_order(first_new);
    auto renamed = [&](int32_t id) { return std::size_t(id) >= first_new ? new_id[std::size_t(id) - first_new] : id; };
    for (auto& output : outputs)
        for (auto& [receiver, l] : output) {
            receiver = renamed(receiver);
            l.source = renamed(l.source);
        }
    place(outputs, progress);
    for (std::size_t r : rays) rays_ += r;
}

void Refiner::place(tbb::enumerable_thread_specific<Output>& outputs, const ProgressFn& progress) {
    // Each receiver's list grows at most once, to its exact size (push_back's doubling would
    // leave up to half of the links' memory, the bulk of the bake's, unused), and the threads'
    // outputs (deques: no spare capacity, no copies as they grow) are freed block by block as
    // their links are placed. The new links of each list are then sorted by source: the threads
    // made them in an order of their own, and the solve sums each list in its order.
    std::vector<uint32_t> added(tree_.nodes.size(), 0);
    std::size_t count = 0;
    for (const auto& output : outputs) {
        for (const auto& [receiver, l] : output) ++added[receiver];
        count += output.size();
    }
    const std::vector<uint32_t> new_links = added;
    std::size_t placed = 0;
    for (auto& output : outputs) {
        for (; !output.empty(); output.pop_front()) {
            const auto& [receiver, l] = output.front();
            std::vector<Link>& links = tree_.nodes[receiver].links;
            if (added[receiver]) links.reserve(links.size() + std::exchange(added[receiver], 0));
            links.push_back(l);
            if (++placed % kLinksPerReport == 0) detail::report_progress(progress, "links", placed, count);
        }
    }
    tbb::parallel_for(std::size_t(0), new_links.size(), [&](std::size_t receiver) {
        if (new_links[receiver] == 0) return;
        std::vector<Link>& links = tree_.nodes[receiver].links;
        std::sort(links.end() - new_links[receiver], links.end(), [](const Link& a, const Link& b) {
            return std::tie(a.source, a.factor, a.uncertainty) < std::tie(b.source, b.factor, b.uncertainty);
        });
    });
}

void Refiner::take_split_snapshot() {
    split_.assign(tree_.nodes.size(), 0);
    for (std::size_t n = 0; n < split_.size(); ++n) split_[n] = tree_.nodes[n].child_count > 0;
}

bool Refiner::split_at_start(int32_t node) const {
    return static_cast<std::size_t>(node) < split_.size() && split_[node];
}

void Refiner::link_initial(const ProgressFn& progress) {
    measure_openness(progress);
    take_split_snapshot();
    // Every cluster's two children see each other; together these pairs cover every pair of
    // patches once in each direction. Lamps light the whole scene through the root.
    std::vector<Pending> pending;
    for (std::size_t n = tree_.patch_count; n < tree_.patch_count + tree_.cluster_count; ++n) {
        const Node& c = tree_.nodes[n];
        pending.push_back({child(c, 0), child(c, 1), false});
        pending.push_back({child(c, 1), child(c, 0), false});
    }
    if (tree_.root >= 0)  // every polygon may have been skipped (degenerate): nothing to light
        for (int32_t lamp : tree_.lamp_nodes) pending.push_back({tree_.root, lamp, false});
    link_all(std::move(pending), std::numeric_limits<double>::infinity(), progress);
}

std::size_t Refiner::refine(double threshold, const ProgressFn& progress) {
    std::vector<int32_t> receivers;
    for (std::size_t n = 0; n < tree_.nodes.size(); ++n)
        if (!tree_.nodes[n].links.empty()) receivers.push_back(static_cast<int32_t>(n));
    take_split_snapshot();
    tbb::enumerable_thread_specific<std::vector<Pending>> pending;
    detail::parallel_rows("links", receivers.size(), 16, 0, progress, [&](std::size_t i) {
        const int32_t receiver = receivers[i];
        Node& r = tree_.nodes[receiver];
        // The errors of a receiver's links add up at its leaves (they often err the same way, as
        // near a corner), so it is their sum that must stay below the threshold: the largest
        // are refined until the rest fit. Links between two nodes that cannot split keep their
        // error whatever is refined; counting it would refine every other link, every round.
        const bool receiver_splits = r.kind == Kind::Cluster || tree_.can_split(r);
        std::vector<std::pair<double, std::size_t>> errors;
        double total = 0.0;
        for (std::size_t k = 0; k < r.links.size(); ++k) {
            if (k + kPrefetchLinks < r.links.size()) prefetch_source(tree_.nodes[r.links[k + kPrefetchLinks].source]);
            const Node& s = tree_.nodes[r.links[k].source];
            if (!receiver_splits && s.kind != Kind::Cluster && !tree_.can_split(s)) continue;
            errors.emplace_back(error(r, r.links[k], split_at_start(receiver)), k);
            total += errors.back().first;
        }
        const double allowed = receiver_threshold(r, threshold);
        if (total <= allowed) return true;
        std::sort(errors.begin(), errors.end(), std::greater<>());
        std::vector<bool> refine_link(r.links.size(), false);
        for (const auto& [link_error, k] : errors) {
            if (total <= allowed) break;
            refine_link[k] = true;
            total -= link_error;
        }
        // Only this task touches r's own list; new links wait below. It is compacted in place:
        // copying it would leave the old list's memory to the allocator, round after round.
        std::size_t kept = 0;
        for (std::size_t k = 0; k < r.links.size(); ++k) {
            if (!refine_link[k]) {
                r.links[kept++] = r.links[k];
                continue;
            }
            pending.local().push_back({receiver, r.links[k].source, true});
            --links_;
        }
        r.links.resize(kept);
        return true;
    });
    std::vector<Pending> all;
    for (const auto& part : pending) all.insert(all.end(), part.begin(), part.end());
    const std::size_t count = all.size();
    link_all(std::move(all), threshold, progress);
    return count;
}

}  // namespace radiosity::hr
