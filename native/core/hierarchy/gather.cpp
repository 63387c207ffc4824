/// @file gather.cpp
/// @brief Links' light at the output corners (hierarchy/gather.h).
#include "hierarchy/gather.h"

#include "common/parallel_rows.h"
#include "hierarchy/links.h"
#include "transport/near_field.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace radiosity::hr {
namespace {

/// The output elements of one leaf: [begin, end) of the mesh (leaf_mesh writes them together).
struct LeafRange {
    std::size_t begin, end;
};

std::vector<LeafRange> leaf_ranges(const std::vector<int32_t>& leaf) {
    std::vector<LeafRange> ranges;
    for (std::size_t e = 0; e < leaf.size(); ++e)
        if (e == 0 || leaf[e] != leaf[e - 1])
            ranges.push_back({e, e + 1});
        else
            ranges.back().end = e + 1;
    return ranges;
}

/// How a link's light varies over its receiver: the geometric part of its transfer at a point.
/// Element sources nearer than ten of their radii: the point-to-polygon factor (Lambert's
/// contour integral). Farther ones: cos cos / r^2 from their centre; clusters: cos / r^2.
class Shape {
public:
    Shape(const Tree& tree, const Node& receiver, const Node& source)
        : tree_(tree), source_(source), normal_(receiver.normal) {
        const float distance = glm::length(source.centre - receiver.centre);
        if (source.is_element() && source.radius > 0.1f * distance) {
            std::array<Vec3, 4> c;
            corner_count_ = element_corners(tree, source, c);
            for (int k = 0; k < corner_count_; ++k) polygon_[k] = glm::dvec3(c[k]);
        }
    }

    /// Element sources: the form factor from `x`, which at() is up to this constant factor.
    double factor_scale() const { return corner_count_ > 0 ? 1.0 : source_.area / M_PI; }

    double at(const Vec3& x) const {
        if (corner_count_ > 0)
            return in_plane_of(tree_, source_, x, normal_)
                       ? 0.0
                       : point_to_polygon(glm::dvec3(x), glm::dvec3(normal_), polygon_, corner_count_,
                                          glm::dvec3(source_.normal));
        const Vec3 d = source_.centre - x;
        if (source_.is_element()) return pair_kernel(normal_, source_.normal, d);
        const double d2 = glm::dot(d, d);
        return d2 > 0.0 ? std::max(0.0f, glm::dot(normal_, d)) / (d2 * std::sqrt(d2)) : 0.0;
    }

private:
    const Tree& tree_;
    const Node& source_;
    Vec3 normal_;
    glm::dvec3 polygon_[4];
    int corner_count_ = 0;
};

/// The share of an element source that `x` sees: rays to `grid` x `grid` jittered points on it,
/// each counted with the kernel cos cos / r^2 of its ends (as the links' own fractions are,
/// hierarchy/links.cpp).
double visible_from(const Tree& tree, const Visibility& visibility, const Vec3& x, const Vec3& normal,
                    const Node& source, int grid, uint32_t seed) {
    std::array<Vec3, 4> to;
    jittered_points(tree, source, grid, seed, to.data());
    double seen = 0.0, total = 0.0;
    for (int k = 0; k < grid * grid; ++k) {
        const double kernel = pair_kernel(normal, source.normal, to[k] - x);
        if (!(kernel > 0.0)) continue;
        total += kernel;
        if (visibility.clear(x, to[k])) seen += kernel;
    }
    return total > 0.0 ? seen / total : 0.0;
}

/// Whether an element's patch is at least an element of the minimum size (hierarchy/gather.h: below
/// that, detail is not resolved).
bool resolved(const Tree& tree, int32_t element) {
    while (tree.nodes[element].parent >= 0 && tree.nodes[tree.nodes[element].parent].is_element())
        element = tree.nodes[element].parent;
    return tree.nodes[element].longest_edge >= tree.min_element_size();
}

}  // namespace

void gather_at_corners(const Tree& tree, const Visibility& visibility, const Elements& mesh,
                       const std::vector<int32_t>& leaf, std::vector<Rgb>& rest, std::vector<Rgb>& corner_light,
                       const ProgressFn& progress) {
    std::vector<LeafRange> ranges = leaf_ranges(leaf);
    ranges.erase(std::remove_if(ranges.begin(), ranges.end(),
                                [&](const LeafRange& r) {
                                    return !(max_channel(mesh.reflectance[r.begin]) > 0.0) || mesh.is_back(r.begin) ||
                                           !resolved(tree, leaf[r.begin]);
                                }),
                 ranges.end());
    detail::parallel_rows("output", ranges.size(), 16, 0, progress, [&](std::size_t i) {
        const LeafRange range = ranges[i];
        // The vertices of the leaf's output elements (each once, however many elements share it),
        // each a hair inside the leaf; `point_of` per element corner.
        const Node& leaf_node = tree.nodes[leaf[range.begin]];
        std::vector<Vec3> points;
        std::vector<int32_t> vertex_ids, point_of;
        for (std::size_t e = range.begin; e < range.end; ++e)
            for (int k = 0; k < (mesh.is_triangle(e) ? 3 : 4); ++k) {
                const int32_t v = mesh.corners[e][k];
                const auto at = std::find(vertex_ids.begin(), vertex_ids.end(), v);
                point_of.push_back(int32_t(at - vertex_ids.begin()));
                if (at != vertex_ids.end()) continue;
                vertex_ids.push_back(v);
                points.push_back(inside(mesh.vertices[v], leaf_node.centre));
            }
        // The links of the leaf and its ancestors, and the light each brings.
        struct Gathered {
            const Node* receiver;
            const Link* link;
            Rgb value;
        };
        std::vector<Gathered> gathered;
        Rgb mean(0.0);
        for (int32_t a = leaf[range.begin]; a >= 0 && tree.nodes[a].is_element(); a = tree.nodes[a].parent) {
            const Node& receiver = tree.nodes[a];
            for (const Link& link : receiver.links) {
                const Node& source = tree.nodes[link.source];
                if (source.is_lamp()) continue;
                const Rgb strength =
                    source.is_element() ? source.radiance : intensity(tree, source, -towards_source(receiver, source));
                const Rgb value = double(link.factor) * strength;
                if (!(max_channel(value) > 0.0)) continue;
                gathered.push_back({&receiver, &link, value});
                mean += value;
            }
        }
        std::vector<Rgb> at_point(points.size(), Rgb(0.0));
        const Node* gauss_of = nullptr;  // the links come receiver by receiver
        std::array<Vec3, 4> gauss;
        int gauss_count = 0;
        for (const auto& [receiver, link, value] : gathered) {
            const Node& source = tree.nodes[link->source];
            if (receiver != gauss_of) {
                gauss_count = element_samples(tree, *receiver, gauss);
                gauss_of = receiver;
            }
            // The link's factor is its geometry's mean over these points times the source's
            // visible share (hierarchy/links.cpp).
            const Shape shape(tree, *receiver, source);
            double over_receiver = 0.0;
            for (int k = 0; k < gauss_count; ++k) over_receiver += shape.at(gauss[k]);
            over_receiver /= gauss_count;
            if (!(over_receiver > 0.0)) {
                for (Rgb& p : at_point) p += value;
                continue;
            }
            // A partly hidden element source: how much of it each corner sees, by its own rays.
            // One ray per corner, as a corner sums many such links and their noise averages
            // out; four for a link that brings a sixteenth of the leaf's light or more.
            const double visible = source.is_element() ? link->factor / (over_receiver * shape.factor_scale()) : 1.0;
            const bool partial = visible > 0.0 && visible < 0.98 && resolved(tree, link->source);
            const int grid = max_channel(value) >= max_channel(mean) / 16.0 ? 2 : 1;
            for (std::size_t p = 0; p < points.size(); ++p) {
                const double seen = partial ? visible_from(tree, visibility, points[p], receiver->normal, source, grid,
                                                           uint32_t(link->source) * 2654435761U + uint32_t(p)) /
                                                  visible
                                            : 1.0;
                at_point[p] += value * (shape.at(points[p]) * seen / over_receiver);
            }
        }
        std::size_t corner = 0;
        for (std::size_t e = range.begin; e < range.end; ++e) {
            rest[e] -= mesh.reflectance[e] * mean;
            for (int k = 0; k < (mesh.is_triangle(e) ? 3 : 4); ++k)
                corner_light[4 * e + k] += mesh.reflectance[e] * at_point[point_of[corner++]];
        }
        return true;
    });
}

bool links_gathered(const Tree& tree, int32_t node) { return tree.nodes[node].is_element() && resolved(tree, node); }

}  // namespace radiosity::hr
