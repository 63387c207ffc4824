/// @file clusters.cpp
/// @brief cluster_elements: greedy pairwise merging of coplanar elements into convex triangles and
/// quads no longer than the element size (clusters.h).
#include "geometry/clusters.h"

#include "common/word_hash.h"
#include "geometry/polygon_geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <unordered_map>

namespace radiosity {
namespace {

using detail::DVec3;

/// Two corners are one straight edge when the turn between them is below this sine: float corners
/// of a subdivided face lie on its edge to about 1e-7 of the coordinates, a few 1e-6 of a small
/// element's edge.
constexpr double kStraightSine = 1e-4;
/// Neighbours are coplanar when their normals differ by less than this cosine (half a degree) and
/// their corners lie within kPlaneDistance of the element size of each other's plane.
const double kCoplanarCosine = std::cos(0.5 * M_PI / 180.0);
constexpr double kPlaneDistance = 1e-3;
/// Room for rounding in the element size bound: faces cut to exactly the size merge.
constexpr double kSizeSlack = 1e-4;
/// A cluster's longest edge against its distance from the nearest point lamp (lamp_edge).
constexpr double kLampDistanceToEdge = 0.5;

/// A group of merged elements: its outline (a convex triangle or quad, CCW about its normal), which
/// of its edges lie on an intersection or contact line (Elements::cut_edges), and what every member
/// shares.
struct Region {
    std::vector<Vec3> corners;
    std::vector<uint8_t> cut;  ///< per edge, from corner k to k + 1
    std::vector<int32_t> members;
    DVec3 normal{0.0};
    int32_t material = 0;
    Rgb reflectance{0.0}, emission{0.0};
    uint8_t side = Elements::kOneSided;  ///< an emitting polygon's fronts and back sides merge apart
    int32_t lattice = 0;                 ///< its plane's Lattice
    double size = 0.0;                   ///< the longest edge it may grow to: its members' polygons' least
    bool alive = true;
};

/// A plane's lattice: two axes in it and the lowest coordinates of its regions' corners along them.
/// Merging along an axis pairs the regions of even column (their lowest coordinate over their width)
/// with the next: a grid of equal faces then merges into aligned rectangles, as a quadtree would,
/// where pairing in any order leaves strips offset by a face that no longer join.
struct Lattice {
    std::array<DVec3, 2> axis;
    std::array<double, 2> origin{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
};

bool textured(const SceneInput& input, int32_t face) {
    const SurfaceTextures* t = input.textures;
    if (t == nullptr) return false;
    return (t->reflectance_texture != nullptr && t->reflectance_texture[face] >= 0) ||
           (t->emission_texture != nullptr && t->emission_texture[face] >= 0);
}

/// Whether element e may merge: an element that is not a lamp's, of an untextured face. An emitting
/// polygon's fronts merge with fronts, its back sides with back sides (alike). (Elements along
/// intersection and contact lines merge too, but never across the line: joined_outline.)
bool mergeable(const Elements& elements, const SceneInput& input, std::size_t e) {
    if (!elements.blocks(e)) return false;
    return !textured(input, elements.polygon[e]);
}

/// The longest edge a cluster holding element e may have beside the point lamps: half the distance
/// from its centre to the nearest. A merged element's form factors come from its centre, and beside
/// a lamp what its faces see of the lamp's fixture, and the fixture's own bright light, change
/// within a distance of the lamp's order; a face at twice its size from every lamp sees them alike.
double lamp_edge(const Elements& elements, std::size_t e, const std::vector<Vec3>& lamps) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Vec3& lamp : lamps) nearest = std::min(nearest, double(glm::distance(elements.centre[e], lamp)));
    return kLampDistanceToEdge * nearest;
}

/// An oriented edge between two corners, by their bits (neighbouring faces' elements meet at
/// bit-identical points: build_elements places shared edge points so), and the side of the regions
/// that have it: an emitting front's edge is its back side's reversed, which is the next front's.
struct EdgeKey {
    std::array<uint32_t, 7> bits;
    bool operator==(const EdgeKey& other) const { return bits == other.bits; }
};

struct EdgeHash {
    std::size_t operator()(const EdgeKey& key) const { return detail::WordsHash()(key.bits); }
};

EdgeKey edge_key(const Vec3& from, const Vec3& to, uint8_t side = Elements::kOneSided) {
    using detail::float_bits;
    return {{float_bits(from.x), float_bits(from.y), float_bits(from.z), float_bits(to.x), float_bits(to.y),
             float_bits(to.z), uint32_t(side)}};
}

/// Where an oriented edge is: its region and the corner it starts at; region -1 when two regions
/// have it (coincident faces), which then merge across it with nobody.
struct EdgeAt {
    int32_t region;
    int corner;
};
using EdgeMap = std::unordered_map<EdgeKey, EdgeAt, EdgeHash>;

EdgeMap edges_of(const std::vector<Region>& regions) {
    EdgeMap map;
    for (std::size_t r = 0; r < regions.size(); ++r) {
        if (!regions[r].alive) continue;
        const std::vector<Vec3>& c = regions[r].corners;
        for (std::size_t k = 0; k < c.size(); ++k) {
            const auto [at, fresh] =
                map.try_emplace(edge_key(c[k], c[(k + 1) % c.size()], regions[r].side), EdgeAt{int32_t(r), int(k)});
            if (!fresh) at->second.region = -1;
        }
    }
    return map;
}

/// An outline and its edges' cut flags (Region).
struct Outline {
    std::vector<Vec3> corners;
    std::vector<uint8_t> cut;
};

/// The outline without its straight corners: the two edges at one become one, on a cut line if
/// either was.
Outline without_straight_corners(Outline outline) {
    std::vector<Vec3>& p = outline.corners;
    for (std::size_t k = 0; k < p.size() && p.size() > 3;) {
        const std::size_t n = p.size(), before = (k + n - 1) % n;
        if (!detail::straight(DVec3(p[before]), DVec3(p[k]), DVec3(p[(k + 1) % n]), kStraightSine)) {
            ++k;
            continue;
        }
        outline.cut[before] |= outline.cut[k];
        p.erase(p.begin() + std::ptrdiff_t(k));
        outline.cut.erase(outline.cut.begin() + std::ptrdiff_t(k));
    }
    return outline;
}

/// The outline of regions a and b joined along a's edge from corner k, which is b's from corner m
/// reversed, if that edge is on no cut line and the outline is a convex triangle or quad.
std::optional<Outline> joined_outline(const Region& a, int k, const Region& b, int m) {
    const std::size_t na = a.corners.size(), nb = b.corners.size(), ka = std::size_t(k), mb = std::size_t(m);
    if (a.cut[ka] || b.cut[mb]) return std::nullopt;
    // Corners a_{k+1} .. a_k, then b_{m+2} .. b_{m-1}; the edges from them a's k+1 .. k-1, then b's m+1 .. m-1.
    Outline outline;
    for (std::size_t i = 1; i <= na; ++i) outline.corners.push_back(a.corners[(ka + i) % na]);
    for (std::size_t i = 2; i < nb; ++i) outline.corners.push_back(b.corners[(mb + i) % nb]);
    for (std::size_t i = 1; i < na; ++i) outline.cut.push_back(a.cut[(ka + i) % na]);
    for (std::size_t i = 1; i < nb; ++i) outline.cut.push_back(b.cut[(mb + i) % nb]);
    outline = without_straight_corners(std::move(outline));
    if (outline.corners.size() > 4) return std::nullopt;
    std::vector<DVec3> points(outline.corners.begin(), outline.corners.end());
    if (!detail::is_convex(points, a.normal)) return std::nullopt;
    return outline;
}

double longest_edge(const std::vector<Vec3>& outline) {
    double longest = 0.0;
    for (std::size_t k = 0; k < outline.size(); ++k)
        longest = std::max(longest, double(glm::length(outline[(k + 1) % outline.size()] - outline[k])));
    return longest;
}

/// Whether two regions are one surface in one plane, on the same side.
bool alike(const Region& a, const Region& b, double plane_distance) {
    if (a.material != b.material || a.reflectance != b.reflectance || a.emission != b.emission || a.side != b.side)
        return false;
    if (glm::dot(a.normal, b.normal) < kCoplanarCosine) return false;
    for (const Vec3& p : b.corners)
        if (std::abs(glm::dot(DVec3(p) - DVec3(a.corners[0]), a.normal)) > plane_distance) return false;
    return true;
}

/// Two axes in the plane of normal n: the world axis least along n, made perpendicular to it, and n x that.
std::array<DVec3, 2> plane_axes(const DVec3& n) {
    const DVec3 a = std::abs(n.x) <= std::abs(n.y) && std::abs(n.x) <= std::abs(n.z) ? DVec3(1, 0, 0)
                    : std::abs(n.y) <= std::abs(n.z)                                 ? DVec3(0, 1, 0)
                                                                                     : DVec3(0, 0, 1);
    const DVec3 u = glm::normalize(a - glm::dot(a, n) * n);
    return {u, glm::cross(n, u)};
}

/// The lowest and highest coordinate of a region's corners along `axis`.
std::array<double, 2> extent(const Region& region, const DVec3& axis) {
    std::array<double, 2> range{std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
    for (const Vec3& p : region.corners) {
        const double t = glm::dot(DVec3(p), axis);
        range = {std::min(range[0], t), std::max(range[1], t)};
    }
    return range;
}

/// The lattices of the regions' planes (one a material, normal and plane offset, at `size` x
/// kPlaneDistance), each region's index into them set.
std::vector<Lattice> plane_lattices(std::vector<Region>& regions, double size) {
    std::map<std::array<int64_t, 5>, int32_t> index;
    std::vector<Lattice> lattices;
    for (Region& region : regions) {
        const DVec3 n = region.normal;
        const double offset = glm::dot(n, DVec3(region.corners[0])) / (kPlaneDistance * size);
        const std::array<int64_t, 5> key{region.material, std::llround(n.x * 1e4), std::llround(n.y * 1e4),
                                         std::llround(n.z * 1e4), std::llround(offset)};
        const auto [at, fresh] = index.try_emplace(key, int32_t(lattices.size()));
        if (fresh) lattices.push_back({plane_axes(n)});
        region.lattice = at->second;
        Lattice& lattice = lattices[std::size_t(at->second)];
        for (int a = 0; a < 2; ++a) lattice.origin[a] = std::min(lattice.origin[a], extent(region, lattice.axis[a])[0]);
    }
    return lattices;
}

/// One region per mergeable element; `region_of` -1 for the others.
std::vector<Region> single_regions(const Elements& elements, const SceneInput& input, const std::vector<Vec3>& lamps,
                                   float size, const std::vector<float>& polygon_edge,
                                   std::vector<int32_t>& region_of) {
    std::vector<Region> regions;
    region_of.assign(elements.size(), -1);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (!mergeable(elements, input, e)) continue;
        Region region;
        const unsigned bits = elements.cut_edges.empty() ? 0u : elements.cut_edges[e];
        for (int k = 0; k < elements.corner_count(e); ++k) {
            region.corners.push_back(elements.vertices[elements.corners[e][k]]);
            region.cut.push_back(uint8_t((bits >> k) & 1u));
        }
        region.members.push_back(int32_t(e));
        region.normal = DVec3(elements.normal[e]);
        region.material = input.material != nullptr ? input.material[elements.polygon[e]] : 0;
        region.reflectance = elements.reflectance[e];
        region.emission = elements.emission[e];
        region.side = elements.side.empty() ? Elements::kOneSided : elements.side[e];
        region.size = std::min(double(polygon_max_edge(polygon_edge, std::size_t(elements.polygon[e]), size)),
                               lamp_edge(elements, e, lamps));
        region_of[e] = int32_t(regions.size());
        regions.push_back(std::move(region));
    }
    return regions;
}

/// A partner of region r this round, and what they form.
struct Partner {
    int32_t region = -1;
    Outline outline;
    double longest = 0.0;
};

/// What a round merges: triangles into quads, along one axis of the planes' lattices, or any pair.
enum class Pairing { Triangles, AlongU, AlongV, Any };

/// What the regions, their edges and this round's merges are.
struct Round {
    std::vector<Region>& regions;
    const std::vector<Lattice>& lattices;
    double size;
    Pairing pairing;
    EdgeMap edges;
    std::vector<char> taken;
};

/// Whether region a may take b across a's edge k in this round's pairing: two triangles; along an
/// axis, a of even column and b the next, as wide along it, across an edge perpendicular to it;
/// any pair.
bool pairs(const Round& round, const Region& a, std::size_t k, const Region& b) {
    if (round.pairing == Pairing::Any) return true;
    if (round.pairing == Pairing::Triangles) return a.corners.size() == 3 && b.corners.size() == 3;
    if (a.corners.size() != 4 || b.corners.size() != 4) return false;
    const Lattice& lattice = round.lattices[std::size_t(a.lattice)];
    const int axis = round.pairing == Pairing::AlongU ? 0 : 1;
    const DVec3 along = lattice.axis[std::size_t(axis)];
    const std::array<double, 2> ra = extent(a, along), rb = extent(b, along);
    const double width = ra[1] - ra[0], tolerance = 1e-3 * width;
    if (!(width > 0.0) || std::llround((ra[0] - lattice.origin[std::size_t(axis)]) / width) % 2 != 0) return false;
    const DVec3 edge = DVec3(a.corners[(k + 1) % 4]) - DVec3(a.corners[k]);
    if (std::abs(glm::dot(edge, along)) > 1e-3 * glm::length(edge)) return false;
    return std::abs(rb[0] - ra[1]) <= tolerance && std::abs(rb[1] - rb[0] - width) <= tolerance;
}

/// The partner of region r this round: the alike, untaken neighbour the pairing allows whose joined
/// outline is convex and has the shortest longest edge within the size.
Partner best_partner(const Round& round, std::size_t r) {
    const Region& a = round.regions[r];
    Partner best;
    for (std::size_t k = 0; k < a.corners.size(); ++k) {
        const auto found = round.edges.find(edge_key(a.corners[(k + 1) % a.corners.size()], a.corners[k], a.side));
        if (found == round.edges.end() || found->second.region < 0) continue;
        const std::size_t n = std::size_t(found->second.region);
        const Region& b = round.regions[n];
        if (n == r || round.taken[n] || !alike(a, b, kPlaneDistance * round.size) || !pairs(round, a, k, b)) continue;
        const std::optional<Outline> outline = joined_outline(a, int(k), b, found->second.corner);
        if (!outline) continue;
        const double longest = longest_edge(outline->corners);
        const double size = std::min(a.size, b.size);
        if (longest > size * (1.0 + kSizeSlack) || (best.region >= 0 && longest >= best.longest)) continue;
        best = {int32_t(n), *outline, longest};
    }
    return best;
}

/// One round: each region merges with at most one partner. Whether any merged.
bool merge_round(std::vector<Region>& regions, const std::vector<Lattice>& lattices, double size, Pairing pairing) {
    Round round{regions, lattices, size, pairing, edges_of(regions), std::vector<char>(regions.size(), 0)};
    bool merged = false;
    for (std::size_t r = 0; r < regions.size(); ++r) {
        if (!regions[r].alive || round.taken[r]) continue;
        Partner partner = best_partner(round, r);
        if (partner.region < 0) continue;
        Region &a = regions[r], &b = regions[std::size_t(partner.region)];
        a.corners = std::move(partner.outline.corners);
        a.cut = std::move(partner.outline.cut);
        a.members.insert(a.members.end(), b.members.begin(), b.members.end());
        a.size = std::min(a.size, b.size);
        b.alive = false;
        round.taken[r] = round.taken[std::size_t(partner.region)] = 1;
        merged = true;
    }
    return merged;
}

/// Merges pairs of regions in rounds: triangles into quads, then along the lattices' axes in turn,
/// then any pair that still can, until no pair merges.
void merge_regions(std::vector<Region>& regions, double size) {
    const std::vector<Lattice> lattices = plane_lattices(regions, size);
    while (merge_round(regions, lattices, size, Pairing::Triangles)) {}
    for (bool merged = true; merged;) {
        const bool along_u = merge_round(regions, lattices, size, Pairing::AlongU);
        const bool along_v = merge_round(regions, lattices, size, Pairing::AlongV);
        merged = along_u || along_v;
    }
    while (merge_round(regions, lattices, size, Pairing::Any)) {}
}

/// Builds the solve elements: vertices shared by position.
class SolveBuilder {
public:
    explicit SolveBuilder(const Elements& output) : output_(output) {
        if (!output.side.empty()) out_.side.reserve(output.size());
    }

    /// Output element e as it is.
    void copy(std::size_t e) {
        std::array<int32_t, 4> c{-1, -1, -1, -1};
        for (int k = 0; k < output_.corner_count(e); ++k) c[k] = vertex(output_.vertices[output_.corners[e][k]]);
        out_.corners.push_back(c);
        out_.centre.push_back(output_.centre[e]);
        out_.normal.push_back(output_.normal[e]);
        out_.area.push_back(output_.area[e]);
        out_.polygon.push_back(output_.polygon[e]);
        out_.reflectance.push_back(output_.reflectance[e]);
        out_.emission.push_back(output_.emission[e]);
        out_.cut_edges.push_back(output_.cut_edges.empty() ? uint8_t(0) : output_.cut_edges[e]);
        if (!output_.side.empty()) out_.side.push_back(output_.side[e]);
        if (!output_.lamp.empty()) out_.lamp.push_back(output_.lamp[e]);
    }

    /// A merged region, as one element with the surface of its first member.
    void merged(const Region& region, std::size_t first) {
        const std::vector<Vec3>& p = region.corners;
        std::array<int32_t, 4> c{-1, -1, -1, -1};
        uint8_t cut = 0;
        for (std::size_t k = 0; k < p.size(); ++k) {
            c[k] = vertex(p[k]);
            cut |= uint8_t(region.cut[k] << k);
        }
        const DVec3 a(p[0]), b(p[1]), d(p[2]);
        DVec3 centre = (a + b + d) / 3.0, twice_area = glm::cross(b - a, d - a);
        if (p.size() == 4) {  // the two triangles' centroids by area, as build_elements' quads
            const DVec3 e(p[3]);
            const DVec3 n1 = twice_area, n2 = glm::cross(d - a, e - a);
            const double w1 = glm::length(n1), w2 = glm::length(n2);
            centre = (w1 * (a + b + d) / 3.0 + w2 * (a + d + e) / 3.0) / (w1 + w2);
            twice_area = n1 + n2;
        }
        out_.corners.push_back(c);
        out_.centre.emplace_back(centre);
        out_.normal.emplace_back(glm::normalize(twice_area));
        out_.area.push_back(float(0.5 * glm::length(twice_area)));
        out_.polygon.push_back(output_.polygon[first]);
        out_.reflectance.push_back(output_.reflectance[first]);
        out_.emission.push_back(output_.emission[first]);
        out_.cut_edges.push_back(cut);
        if (!output_.side.empty()) out_.side.push_back(region.side);
        if (!output_.lamp.empty()) out_.lamp.push_back(0);
    }

    int32_t last() const { return int32_t(out_.size()) - 1; }
    Elements take() { return std::move(out_); }

private:
    int32_t vertex(const Vec3& p) {
        const auto [at, fresh] = vertex_of_.try_emplace(edge_key(p, p), int32_t(out_.vertices.size()));
        if (fresh) out_.vertices.push_back(p);
        return at->second;
    }

    const Elements& output_;
    Elements out_;
    std::unordered_map<EdgeKey, int32_t, EdgeHash> vertex_of_;
};

}  // namespace

Clusters cluster_elements(const Elements& output, const SceneInput& input, float element_size,
                          const std::vector<Vec3>& lamps, const std::vector<float>& polygon_edge) {
    Clusters clusters;
    if (!(element_size > 0.0f)) return clusters;
    std::vector<int32_t> region_of;
    std::vector<Region> regions = single_regions(output, input, lamps, element_size, polygon_edge, region_of);
    merge_regions(regions, double(element_size));
    bool any = false;
    for (const Region& region : regions) {
        if (!region.alive) continue;
        any = any || region.members.size() > 1;
        for (const int32_t e : region.members) region_of[std::size_t(e)] = int32_t(&region - regions.data());
    }
    if (!any) return clusters;

    // Each merged region becomes one element where its first member (in the output's order) was,
    // so emitting fronts stay before the back sides.
    SolveBuilder build(output);
    std::vector<int32_t> element_of_region(regions.size(), -1);
    clusters.of_element.assign(output.size(), -1);
    for (std::size_t e = 0; e < output.size(); ++e) {
        const int32_t r = region_of[e];
        if (r < 0 || regions[std::size_t(r)].members.size() == 1) {
            build.copy(e);
            clusters.of_element[e] = build.last();
            continue;
        }
        if (element_of_region[std::size_t(r)] < 0) {
            build.merged(regions[std::size_t(r)], e);
            element_of_region[std::size_t(r)] = build.last();
        }
        clusters.of_element[e] = element_of_region[std::size_t(r)];
    }
    clusters.elements = build.take();
    return clusters;
}

}  // namespace radiosity
