/// @file output.cpp
/// @brief Leaves to a conforming mesh (hierarchy/output.h).
#include "hierarchy/output.h"

#include "common/report_progress.h"
#include "hierarchy/conform.h"

#include <glm/geometric.hpp>

#include <unordered_map>

namespace radiosity::hr {
namespace {

constexpr std::size_t kPatchesPerReport = 65536;  ///< a small part of a second of the leaf mesh
constexpr std::size_t kMostPointsToSplit = 256;   ///< see MeshWriter::split_leaf

/// Appends the vertices along a -> b, from a up to but without b, where neighbours split it.
void edge_vertices(const Tree& tree, int32_t a, int32_t b, std::vector<int32_t>& out) {
    const int32_t m = tree.existing_midpoint(a, b);
    if (m < 0) {
        out.push_back(a);
        return;
    }
    edge_vertices(tree, a, m, out);
    edge_vertices(tree, m, b, out);
}

class MeshWriter {
public:
    MeshWriter(const Tree& tree, const BuildResult& build, const std::vector<Rgb>& lamp_light, LeafMesh& mesh)
        : tree_(tree), build_(build), lamp_light_(lamp_light), mesh_(mesh) {}

    void leaf(int32_t id) {
        const Node& n = tree_.nodes[id];
        leaf_ = id;
        lamp_part_ = n.reflectance * lamp_light_[id];
        emission_ = n.emission + lamp_part_;
        polygon_ = build_.elements.polygon[n.patch];
        take_cuts(n.patch);
        ++mesh_.leaves;
        const int count = n.is_triangle() ? 3 : 4;
        boundary_.clear();
        on_edges_.clear();
        for (int k = 0; k < count; ++k) {
            const std::size_t first = boundary_.size();
            edge_vertices(tree_, n.corners[k], n.corners[(k + 1) % count], boundary_);
            on_edges_.resize(boundary_.size(), uint8_t(1u << k));
            on_edges_[first] |= uint8_t(1u << ((k + count - 1) % count));  // corner k also ends edge k - 1
        }
        if (static_cast<int>(boundary_.size()) == count) {
            std::array<int32_t, 4> corners{-1, -1, -1, -1};
            for (int k = 0; k < count; ++k) corners[k] = vertex(n.corners[k]);
            add(n, corners);
            return;
        }
        split_leaf(n);
    }

    /// The output vertex of tree vertex `v` in the current leaf's input polygon. Each polygon has
    /// its own vertices, as bake()'s elements do: an input corner then names one polygon's
    /// colour (neighbours still meet at equal positions, where interpolation welds them).
    int32_t vertex(int32_t v) { return vertex_in(polygon_, v); }

    int32_t vertex_in(int32_t polygon, int32_t v) {
        const auto key = (static_cast<uint64_t>(static_cast<uint32_t>(polygon)) << 32) | static_cast<uint32_t>(v);
        const auto [it, made] = local_.try_emplace(key, static_cast<int32_t>(mesh_.elements.vertices.size()));
        if (made) mesh_.elements.vertices.push_back(tree_.vertices[v]);
        return it->second;
    }

private:
    /// A leaf with vertices on its edges (boundary_), in as few elements as keep them all
    /// (hierarchy/conform.h): neighbours then share every vertex on their common edge. The split's cost
    /// grows as the cube of the vertices (25 ms at 258): a leaf with more, a large dark polygon
    /// beside finely split ones, is fanned from its centre instead.
    void split_leaf(const Node& n) {
        if (boundary_.size() > kMostPointsToSplit) {
            fan(n);
            return;
        }
        points_.clear();
        for (int32_t v : boundary_) points_.push_back(tree_.vertices[v]);
        pieces_.clear();
        splitter_.split(points_, on_edges_, pieces_);
        for (const auto& piece : pieces_) {
            std::array<int32_t, 4> corners{-1, -1, -1, -1};
            for (int k = 0; k < (piece[3] < 0 ? 3 : 4); ++k) corners[k] = vertex(boundary_[piece[k]]);
            add(n, corners);
        }
    }

    void fan(const Node& n) {
        Elements& out = mesh_.elements;
        const auto centre = static_cast<int32_t>(out.vertices.size());
        out.vertices.push_back(n.centre);
        for (std::size_t k = 0; k < boundary_.size(); ++k)
            add(n, {centre, vertex(boundary_[k]), vertex(boundary_[(k + 1) % boundary_.size()]), -1});
    }

    /// The edges of `patch` that lie on an intersection or contact line (Elements::cut_edges).
    void take_cuts(int32_t patch) {
        cuts_.clear();
        const Elements& patches = build_.elements;
        if (patches.cut_edges.empty() || patches.cut_edges[patch] == 0) return;
        const int count = patches.is_triangle(patch) ? 3 : 4;
        for (int k = 0; k < count; ++k)
            if ((patches.cut_edges[patch] >> k) & 1u)
                cuts_.push_back({patches.vertices[patches.corners[patch][k]],
                                 patches.vertices[patches.corners[patch][(k + 1) % count]]});
    }

    /// Whether the output edge a - b lies along one of the current patch's cut edges.
    bool on_cut(const Vec3& a, const Vec3& b) const {
        for (const auto& [p, q] : cuts_) {
            const glm::dvec3 d(q - p);
            const double length2 = glm::dot(d, d);
            auto on_line = [&](const Vec3& x) {
                const glm::dvec3 v(x - p);
                const double t = glm::dot(v, d) / length2;
                return t > -1e-5 && t < 1.0 + 1e-5 && glm::dot(v - t * d, v - t * d) <= 1e-10 * length2;
            };
            if (length2 > 0.0 && on_line(a) && on_line(b)) return true;
        }
        return false;
    }

    void add(const Node& n, const std::array<int32_t, 4>& corners) {
        Elements& out = mesh_.elements;
        const int count = corners[3] < 0 ? 3 : 4;
        // Leaves keep their patch's cut edges: corner colours must not blend across a contact
        // line (lit floor beside the dark footprint of a block standing on it).
        if (!build_.elements.cut_edges.empty()) {
            uint8_t bits = 0;
            for (int k = 0; k < count; ++k)
                if (on_cut(out.vertices[corners[k]], out.vertices[corners[(k + 1) % count]])) bits |= uint8_t(1u << k);
            out.cut_edges.push_back(bits);
        }
        Vec3 centre(0.0f);
        glm::dvec3 twice(0.0);
        for (int k = 0; k < count; ++k) {
            const Vec3& p = out.vertices[corners[k]];
            centre += p / float(count);
            if (k >= 1 && k + 1 < count)
                twice += glm::cross(glm::dvec3(p - out.vertices[corners[0]]),
                                    glm::dvec3(out.vertices[corners[k + 1]] - out.vertices[corners[0]]));
        }
        out.corners.push_back(corners);
        out.centre.push_back(centre);
        out.normal.push_back(n.normal);
        out.area.push_back(static_cast<float>(0.5 * glm::length(twice)));
        out.polygon.push_back(polygon_);
        out.reflectance.push_back(n.reflectance);
        out.emission.push_back(emission_);
        // An emitter's back side (its own patches, Elements::side) stays one: solved, not written.
        if (!build_.elements.side.empty()) out.side.push_back(build_.elements.side[n.patch]);
        mesh_.radiance.push_back(n.radiance);
        mesh_.lamp_part.push_back(lamp_part_);
        mesh_.leaf.push_back(leaf_);
    }

    const Tree& tree_;
    const BuildResult& build_;
    const std::vector<Rgb>& lamp_light_;
    LeafMesh& mesh_;
    Rgb emission_{0.0}, lamp_part_{0.0};
    int32_t leaf_ = -1, polygon_ = -1;
    std::unordered_map<uint64_t, int32_t> local_;
    std::vector<int32_t> boundary_;  ///< the current leaf's vertices: corners and those on its edges
    std::vector<uint8_t> on_edges_;  ///< per boundary vertex: bit k when on the leaf's edge k
    std::vector<Vec3> points_;
    std::vector<std::array<int32_t, 4>> pieces_;
    LeafSplitter splitter_;
    std::vector<std::pair<Vec3, Vec3>> cuts_;
};

void visit_leaves(const Tree& tree, int32_t id, MeshWriter& writer) {
    const Node& n = tree.nodes[id];
    if (n.is_leaf()) {
        writer.leaf(id);
        return;
    }
    for (int k = 0; k < n.child_count; ++k) visit_leaves(tree, child(n, k), writer);
}

}  // namespace

LeafMesh leaf_mesh(const Tree& tree, const BuildResult& build, const std::vector<Rgb>& lamp_light,
                   const ProgressFn& progress) {
    LeafMesh mesh;
    MeshWriter writer(tree, build, lamp_light, mesh);
    for (std::size_t p = 0; p < tree.patch_count; ++p) {
        if (p % kPatchesPerReport == 0) detail::report_progress(progress, "output", p, tree.patch_count);
        visit_leaves(tree, static_cast<int32_t>(p), writer);
    }
    // Input corners: build vertex -> (its polygon, welded tree vertex) -> output vertex.
    const Elements& patches = build.elements;
    std::vector<int32_t> polygon_of_vertex(patches.vertices.size(), -1);
    for (std::size_t p = 0; p < patches.size(); ++p)
        for (int k = 0; k < (patches.is_triangle(p) ? 3 : 4); ++k)
            polygon_of_vertex[patches.corners[p][k]] = patches.polygon[p];
    mesh.elements.corner_vertex.reserve(patches.corner_vertex.size());
    for (int32_t v : patches.corner_vertex)
        mesh.elements.corner_vertex.push_back(v < 0 ? -1
                                                    : writer.vertex_in(polygon_of_vertex[v], tree.patch_vertex[v]));
    return mesh;
}

}  // namespace radiosity::hr
