/// @file tree.h
/// @brief The node tree of hierarchical radiosity (internal): clusters above the patches,
/// quadtree elements below them, lamps beside them, and the links each node gathers along.
#pragma once

#include "geometry/surface_textures.h"
#include "hierarchy/hierarchy.h"

#include <tbb/concurrent_vector.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <map>
#include <mutex>
#include <vector>

namespace radiosity::hr {

enum class Kind : uint8_t { Element, Cluster, PointLamp, Sun };

/// A non-negative float kept to 8 significant bits (bfloat16, rounded to nearest): enough for an
/// error estimate that only decides what to refine, in half the bytes of a float.
class RoughFloat {
public:
    RoughFloat(float value = 0.0f) {
        uint32_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        bits_ = static_cast<uint16_t>((bits + 0x7fffu + ((bits >> 16) & 1u)) >> 16);
    }
    operator float() const {
        const uint32_t bits = uint32_t(bits_) << 16;
        float value;
        std::memcpy(&value, &bits, sizeof value);
        return value;
    }

private:
    uint16_t bits_ = 0;
};

/// Light gathered by a receiver from one source. Element from element: G += factor * L_source.
/// Otherwise the source is a point source seen along towards_source() (receiver to source, unit):
/// G += factor * intensity(source, -direction), where `factor` holds V cos_r / (pi r^2) (no cos_r
/// for cluster receivers, which bin it by direction; 1/pi instead of 1/(pi r^2) for suns).
/// The direction is not stored: links are most of a bake's memory, and both ends know it.
struct Link {
    int32_t source = -1;
    float factor = 0.0f;
    /// The link's radiance error per unit of the source's strength (its radiance, or its intensity
    /// towards the receiver), reflectance included: refinement compares it with the threshold
    /// again whenever the sources brighten, without tracing rays anew.
    float uncertainty = 0.0f;
    /// Element sources: the error per unit of how much the source's radiance varies over it
    /// (the link uses its mean, and where it is partly hidden or near, the mean misleads).
    RoughFloat source_doubt = 0.0f;
    /// Added to `uncertainty` once the receiver has children: the link's light reaches them all
    /// alike, so a gradient under it shows as steps (a leaf's corners interpolate it instead).
    RoughFloat steps = 0.0f;
};

/// Per channel: max(0, M . u) + (S - |M|) / 4 is a cluster's intensity towards u (hierarchy.h).
struct Emitter {
    Rgb power{0.0};                      ///< S = sum L A
    std::array<glm::dvec3, 3> moment{};  ///< M = sum L A n, per channel
    Rgb moment_length{0.0};              ///< |M| per channel (intensity() reads it on every link, every sweep)
};

/// A cluster's two children and the first one's share of the power (after each solve) and of the
/// area: all that cluster_samples' walks down the tree read at each level. Kept in a small array
/// apart from the nodes: reading a whole node per level missed the cache at every step, a fifth
/// of the link phase's time.
struct ClusterSplit {
    std::array<int32_t, 2> child{-1, -1};
    float power_share = 0.5f, area_share = 0.5f;
};

/// Six direction bins (+x, -x, +y, -y, +z, -z) of gathered light at normal incidence.
using AmbientCube = std::array<Rgb, 6>;

struct Node {
    Kind kind = Kind::Element;
    /// Patches: the weld (Tree's vertices) made two of its corners one, or left its corners no
    /// area: a sliver thinner than the weld tolerance (a contact cut between two block sides a
    /// hundredth of a millimetre apart). It stays whole: its children would have no area, and the
    /// push-pull's area mean of them would be 0 / 0.
    bool collapsed = false;
    int32_t parent = -1;
    int32_t first_child = -1;   ///< elements: 4 contiguous children; clusters: 2, see child()
    int32_t second_child = -1;  ///< clusters only
    int32_t child_count = 0;
    int32_t lamp = -1;     ///< index into Lights::points or ::suns for lamp nodes
    int32_t cluster = -1;  ///< clusters: index into Tree::emitters, ::cubes and ::splits
    // Geometry (fixed once the node exists).
    std::array<int32_t, 4> corners{-1, -1, -1, -1};  ///< elements: vertex ids, [3] = -1 for triangles
    int32_t patch = -1;                              ///< elements: the patch they split from (its polygon, material)
    int32_t patch_begin = 0, patch_end = 0;          ///< clusters: range of Tree::patch_order
    Vec3 centre{0.0f}, normal{0.0f};
    float area = 0.0f;
    float radius = 0.0f;  ///< bounding sphere about `centre`
    float longest_edge = 0.0f;
    Rgb reflectance{0.0}, emission{0.0};  ///< clusters: the largest reflectance inside
    // Solution.
    Rgb radiance{0.0};                                ///< elements: mean leaving radiance
    float radiance_low = 0.0f, radiance_high = 0.0f;  ///< elements: range of the leaves below (largest channel)
    Rgb gathered{0.0};                                ///< elements: this sweep's sum over links
    std::vector<Link> links;                          ///< what this node gathers from

    bool is_element() const { return kind == Kind::Element; }
    bool is_leaf() const { return child_count == 0; }
    bool is_triangle() const { return corners[3] < 0; }
    bool is_lamp() const { return kind == Kind::PointLamp || kind == Kind::Sun; }
};

/// Asks for the lines of node `n` that a link's reader takes (kind and centre, radiance) before it
/// needs them: a receiver's sources lie anywhere among the nodes, so each read of one waits for
/// memory unless it was asked for a few links ahead.
inline void prefetch_source(const Node& n) {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(&n.kind);
    __builtin_prefetch(&n.radiance);
#else
    (void)n;
#endif
}

/// Links read ahead of the one being summed (prefetch_source).
constexpr std::size_t kPrefetchLinks = 8;

/// The unit direction from `receiver` to a source it gathers from as a point (a sun: towards it).
inline Vec3 towards_source(const Node& receiver, const Node& source) {
    return source.kind == Kind::Sun ? -source.normal : glm::normalize(source.centre - receiver.centre);
}

/// cos cos / r^2 between a point with unit normal `n` and one with unit normal `m`, `d` from the
/// first to the second (not normalised: hence / r^4); 0 where either faces away or they meet.
inline double pair_kernel(const Vec3& n, const Vec3& m, const Vec3& d) {
    const float d2 = glm::dot(d, d);
    return d2 > 0.0f ? std::max(0.0f, glm::dot(n, d)) * std::max(0.0f, -glm::dot(m, d)) / (d2 * d2) : 0.0;
}

/// An element's power: its radiance over its area.
inline Rgb element_power(const Node& n) { return n.radiance * double(n.area); }

/// An element's emitter: its power, along its normal.
inline Emitter element_emitter(const Node& n) {
    Emitter e;
    e.power = element_power(n);
    for (int c = 0; c < 3; ++c) e.moment[c] = e.power[c] * glm::dvec3(n.normal);
    e.moment_length = e.power * double(glm::length(n.normal));
    return e;
}

/// Child k of a node with children.
inline int32_t child(const Node& n, int k) {
    return n.kind == Kind::Cluster && k == 1 ? n.second_child : n.first_child + k;
}

/// Nodes and vertices may grow from several threads at once (refinement): both live in
/// concurrent vectors, whose elements never move.
class Tree {
public:
    /// Patches from `build` (node i = patch i), clusters above them, one node per lamp.
    Tree(const BuildResult& build, const Lights& lights, float min_element_size, std::size_t max_leaves);

    tbb::concurrent_vector<Node> nodes;
    tbb::concurrent_vector<Vec3> vertices;  ///< welded patch vertices, then midpoints and centres
    std::vector<int32_t> patch_order;       ///< patches in cluster order
    std::vector<int32_t> patch_vertex;      ///< build vertex -> welded vertex id
    const Lights& lights;
    int32_t root = -1;
    std::size_t patch_count = 0, cluster_count = 0;
    std::vector<int32_t> lamp_nodes;
    /// Per cluster (Node::cluster), kept apart from the nodes, most of which are elements: what
    /// it emits, pulled up from its leaves, and this sweep's light gathered on its links, binned.
    std::vector<Emitter> emitters;
    std::vector<AmbientCube> cubes;
    std::vector<ClusterSplit> splits;
    std::vector<Vec3> patch_centres;     ///< per patch: Node::centre, where those walks end
    std::vector<int32_t> patch_polygon;  ///< per patch: its input polygon (Elements::polygon)
    /// Image textures of the faces (null: none): an element split from a textured patch takes
    /// its own mean colour over its part of the face, not its parent's.
    const detail::FaceTextures* textures = nullptr;
    /// Per patch (empty: no World): the World's light arriving, irradiance / pi, its mean over the
    /// patch. Its first reflection is part of every element's emission (reflectance x this).
    std::vector<Rgb> world_light;
    float scene_size = 0.0f;  ///< bounding box diagonal, metres
    /// Points closer than this are one vertex (detail::weld_tolerance), and a point closer than
    /// this to a plane lies in it (in_plane_of).
    float weld_tolerance = 0.0f;

    /// Splits element `e` into four (once; safe to call from several threads). Returns false when
    /// it is too small to split (its children's longest edges would be below `finest`, by default
    /// the minimum element size) or the leaf cap is reached.
    bool subdivide(int32_t e) { return subdivide(e, min_element_size_); }
    bool subdivide(int32_t e, float finest);
    /// What a cluster or element emits, as a point source (intensity(), hierarchy/links.h).
    Emitter emitter(const Node& n) const { return n.kind == Kind::Cluster ? emitters[n.cluster] : element_emitter(n); }
    /// Its emitter's power alone (S = sum L A).
    Rgb power(const Node& n) const { return n.kind == Kind::Cluster ? emitters[n.cluster].power : element_power(n); }
    bool can_split(const Node& n) const { return can_split(n, min_element_size_); }
    bool can_split(const Node& n, float finest) const {
        return n.is_element() && !n.collapsed && n.longest_edge >= 2.0f * finest;
    }
    float min_element_size() const { return min_element_size_; }
    /// The vertex halfway along a - b, made once and shared by both elements at that edge.
    int32_t midpoint(int32_t a, int32_t b);
    /// The vertex at a - b's midpoint if an element split that edge, else -1 (after refinement).
    int32_t existing_midpoint(int32_t a, int32_t b) const;
    std::size_t leaves() const { return leaves_; }
    /// Gives the nodes made since `first` (elements split by threads in whatever order they ran)
    /// the ids one thread would give them: each split node's children together, split nodes
    /// taken in the order of their ids, breadth first. Ids then depend on the scene alone, and so
    /// does everything that follows them (the order of links, seeds). Returns each of those
    /// nodes' new id (index: old id - first); ids held outside the nodes are the caller's to map.
    std::vector<int32_t> number_in_order(std::size_t first);
    /// Whether a split was refused because the leaves reached the cap.
    bool cap_reached() const { return cap_reached_; }

private:
    int32_t build_cluster(int32_t begin, int32_t end, int32_t parent);
    void fill_element(Node& n, const Node& parent);

    float min_element_size_ = 0.0f;
    std::size_t max_leaves_ = 0;
    std::atomic<std::size_t> leaves_{0};
    std::atomic<bool> cap_reached_{false};
    std::array<std::mutex, 256> split_locks_;
    mutable std::mutex midpoint_lock_;
    std::map<std::pair<int32_t, int32_t>, int32_t> midpoints_;
};

/// The input polygon node `n` lies on (-1 for clusters and lamps): what an error names.
inline int32_t input_polygon(const Tree& tree, const Node& n) {
    return n.is_element() && n.patch >= 0 ? tree.patch_polygon[n.patch] : -1;
}

/// Whether a point `x` of a face with unit normal `normal` lies in element `source`'s plane, that
/// face parallel to it (back to back, or face to face in contact), within the weld tolerance.
/// Round-off alone puts such a point a hair in front of the plane or behind it, and a polygon a
/// hair in front covers the point's whole hemisphere: its factor would be 0 or 1 by chance (an
/// emitter's unlit back gathered three quarters of its light). Faces across an edge from the
/// source (a wall beside a floor) are not parallel to it: a point at their common edge sees it.
inline bool in_plane_of(const Tree& tree, const Node& source, const Vec3& x, const Vec3& normal) {
    return std::abs(glm::dot(source.normal, normal)) > 0.999f &&
           std::abs(glm::dot(source.normal, x - tree.vertices[source.corners[0]])) <= tree.weld_tolerance;
}

/// Sample points of an element for the factor and visibility estimates: 2 x 2 Gauss-Legendre
/// points of its bilinear map (quads) or the 3-point rule's points (triangles). Returns the count.
int element_samples(const Tree& tree, const Node& n, std::array<Vec3, 4>& points);

/// `grid` x `grid` points of an element, one placed at random (by `seed`) in each cell of its
/// parameter square (quads: bilinear; triangles: the square mapped onto them by area), for
/// unbiased visibility. Writes grid^2 points.
void jittered_points(const Tree& tree, const Node& n, int grid, uint32_t seed, Vec3* points);

/// Points near an element's corners (a tenth of the way to its centre) and its centre: where a
/// transfer varying across the element shows its extremes, which symmetric Gauss points can hide.
int element_probes(const Tree& tree, const Node& n, std::array<Vec3, 5>& points);

/// Corner positions of an element.
int element_corners(const Tree& tree, const Node& n, std::array<Vec3, 4>& corners);

/// A corner moved a hair (1e-4 of the way) towards its element's centre: the element's own side
/// of a shadow edge or contact line through the corner, and off any polygon edge there.
inline Vec3 inside(const Vec3& corner, const Vec3& centre) { return corner + 1e-4f * (centre - corner); }

}  // namespace radiosity::hr
