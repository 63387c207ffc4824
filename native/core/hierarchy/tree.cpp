/// @file tree.cpp
/// @brief Builds the hierarchy's tree: welded patches, a median-split cluster tree, lamp nodes,
/// and splits elements into four on demand.
#include "hierarchy/tree.h"

#include "common/stratified.h"
#include "geometry/weld.h"

#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radiosity::hr {
namespace {

float longest_edge(const std::array<Vec3, 4>& p, int count) {
    float longest = 0.0f;
    for (int k = 0; k < count; ++k) longest = std::max(longest, glm::length(p[(k + 1) % count] - p[k]));
    return longest;
}

float polygon_area(const std::array<Vec3, 4>& p, int count) {
    glm::dvec3 twice(0.0);
    for (int k = 1; k + 1 < count; ++k) twice += glm::cross(glm::dvec3(p[k] - p[0]), glm::dvec3(p[k + 1] - p[0]));
    return static_cast<float>(0.5 * glm::length(twice));
}

}  // namespace

int element_corners(const Tree& tree, const Node& n, std::array<Vec3, 4>& corners) {
    const int count = n.is_triangle() ? 3 : 4;
    for (int k = 0; k < count; ++k) corners[k] = tree.vertices[n.corners[k]];
    return count;
}

int element_samples(const Tree& tree, const Node& n, std::array<Vec3, 4>& points) {
    std::array<Vec3, 4> c;
    if (element_corners(tree, n, c) == 3) {
        for (int k = 0; k < 3; ++k)
            points[k] = (4.0f * c[k] + c[(k + 1) % 3] + c[(k + 2) % 3]) / 6.0f;  // (2/3, 1/6, 1/6)
        return 3;
    }
    const float g[2] = {0.2113249f, 0.7886751f};  // (1 -+ 1/sqrt 3) / 2
    for (int k = 0; k < 4; ++k) {
        const float u = g[k & 1], v = g[k >> 1];
        points[k] = (1 - u) * (1 - v) * c[0] + u * (1 - v) * c[1] + u * v * c[2] + (1 - u) * v * c[3];
    }
    return 4;
}

void jittered_points(const Tree& tree, const Node& n, int grid, uint32_t seed, Vec3* points) {
    std::array<Vec3, 4> c;
    const int count = element_corners(tree, n, c);
    detail::stratified_points(c.data(), count, grid, seed, points);
}

int element_probes(const Tree& tree, const Node& n, std::array<Vec3, 5>& points) {
    std::array<Vec3, 4> c;
    const int count = element_corners(tree, n, c);
    for (int k = 0; k < count; ++k) points[k] = 0.9f * c[k] + 0.1f * n.centre;
    points[count] = n.centre;
    return count + 1;
}

Tree::Tree(const BuildResult& build, const Lights& lights_in, float min_element_size, std::size_t max_leaves)
    : lights(lights_in), min_element_size_(min_element_size), max_leaves_(max_leaves) {
    const Elements& e = build.elements;
    std::size_t welded = 0;
    weld_tolerance = detail::weld_tolerance(e.vertices);
    patch_vertex = detail::weld_points(e.vertices, weld_tolerance, welded);
    vertices.grow_by(welded);
    for (std::size_t v = 0; v < e.vertices.size(); ++v) vertices[patch_vertex[v]] = e.vertices[v];

    patch_count = e.size();
    leaves_ = patch_count;
    nodes.grow_by(patch_count);
    Vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (std::size_t p = 0; p < patch_count; ++p) {
        Node& n = nodes[p];
        n.patch = static_cast<int32_t>(p);
        const int count = e.is_triangle(p) ? 3 : 4;
        std::array<Vec3, 4> c;
        for (int k = 0; k < count; ++k) {
            n.corners[k] = patch_vertex[e.corners[p][k]];
            c[k] = vertices[n.corners[k]];
            low = glm::min(low, c[k]);
            high = glm::max(high, c[k]);
        }
        n.centre = e.centre[p];
        n.normal = e.normal[p];
        n.area = e.area[p];
        n.longest_edge = longest_edge(c, count);
        for (int k = 0; k < count; ++k) n.collapsed = n.collapsed || n.corners[k] == n.corners[(k + 1) % count];
        n.collapsed = n.collapsed || !(polygon_area(c, count) > 0.0f);
        for (int k = 0; k < count; ++k) n.radius = std::max(n.radius, glm::length(c[k] - n.centre));
        n.reflectance = e.reflectance[p];
        n.emission = e.emission[p];
        n.radiance = n.emission;
    }
    scene_size = patch_count ? glm::length(high - low) : 0.0f;

    patch_order.resize(patch_count);
    for (std::size_t p = 0; p < patch_count; ++p) patch_order[p] = static_cast<int32_t>(p);
    if (patch_count) root = build_cluster(0, static_cast<int32_t>(patch_count), -1);
    cluster_count = nodes.size() - patch_count;
    emitters.resize(cluster_count);
    cubes.resize(cluster_count);
    // What cluster_samples' walks read, apart from the nodes.
    splits.resize(cluster_count);
    patch_centres.resize(patch_count);
    for (std::size_t p = 0; p < patch_count; ++p) patch_centres[p] = nodes[p].centre;
    patch_polygon = e.polygon;
    for (std::size_t k = 0; k < cluster_count; ++k) {
        const Node& c = nodes[patch_count + k];
        const float left = nodes[c.first_child].area, right = nodes[c.second_child].area;
        const float share = left + right > 0.0f ? left / (left + right) : 0.5f;
        splits[k] = {{c.first_child, c.second_child}, share, share};
    }

    auto add_lamp = [&](Kind kind, std::size_t index) -> Node& {
        lamp_nodes.push_back(static_cast<int32_t>(nodes.size()));
        Node& n = *nodes.grow_by(1);
        n.kind = kind;
        n.lamp = static_cast<int32_t>(index);
        return n;
    };
    for (std::size_t l = 0; l < lights.points.size(); ++l)
        add_lamp(Kind::PointLamp, l).centre = lights.points[l].position;
    for (std::size_t l = 0; l < lights.suns.size(); ++l) add_lamp(Kind::Sun, l).normal = lights.suns[l].direction;
}

int32_t Tree::build_cluster(int32_t begin, int32_t end, int32_t parent) {
    if (end - begin == 1) {
        nodes[patch_order[begin]].parent = parent;
        return patch_order[begin];
    }
    Vec3 low(std::numeric_limits<float>::max()), high(-low), centre_low = low, centre_high = high;
    float area = 0.0f;
    Rgb reflectance(0.0);
    for (int32_t i = begin; i < end; ++i) {
        const Node& p = nodes[patch_order[i]];
        low = glm::min(low, p.centre - Vec3(p.radius));
        high = glm::max(high, p.centre + Vec3(p.radius));
        centre_low = glm::min(centre_low, p.centre);
        centre_high = glm::max(centre_high, p.centre);
        area += p.area;
        reflectance = glm::max(reflectance, p.reflectance);
    }
    const auto id = static_cast<int32_t>(nodes.size());
    {
        Node& c = *nodes.grow_by(1);
        c.kind = Kind::Cluster;
        c.cluster = id - static_cast<int32_t>(patch_count);
        c.parent = parent;
        c.patch_begin = begin;
        c.patch_end = end;
        c.centre = 0.5f * (low + high);
        c.radius = 0.5f * glm::length(high - low);
        c.area = area;
        c.reflectance = reflectance;
    }
    // Median split along the longest axis of the patch centres: a balanced tree, depth log2(n).
    const Vec3 extent = centre_high - centre_low;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const int32_t middle = begin + (end - begin) / 2;
    std::nth_element(patch_order.begin() + begin, patch_order.begin() + middle, patch_order.begin() + end,
                     [&](int32_t a, int32_t b) { return nodes[a].centre[axis] < nodes[b].centre[axis]; });
    const int32_t left = build_cluster(begin, middle, id);
    const int32_t right = build_cluster(middle, end, id);
    Node& c = nodes[id];
    c.first_child = left;
    c.child_count = 2;
    c.second_child = right;
    return id;
}

int32_t Tree::midpoint(int32_t a, int32_t b) {
    const auto key = std::minmax(a, b);
    std::lock_guard<std::mutex> lock(midpoint_lock_);
    auto [it, made] = midpoints_.try_emplace({key.first, key.second}, -1);
    if (made) {
        const Vec3 m = 0.5f * (vertices[a] + vertices[b]);
        it->second = static_cast<int32_t>(vertices.push_back(m) - vertices.begin());
    }
    return it->second;
}

int32_t Tree::existing_midpoint(int32_t a, int32_t b) const {
    const auto key = std::minmax(a, b);
    std::lock_guard<std::mutex> lock(midpoint_lock_);
    const auto it = midpoints_.find({key.first, key.second});
    return it == midpoints_.end() ? -1 : it->second;
}

void Tree::fill_element(Node& n, const Node& parent) {
    std::array<Vec3, 4> c;
    const int count = element_corners(*this, n, c);
    n.patch = parent.patch;
    n.normal = parent.normal;
    n.reflectance = parent.reflectance;
    n.emission = parent.emission;
    const auto polygon = std::size_t(patch_polygon[std::size_t(n.patch)]);
    if (textures && textures->textured(polygon)) {
        const detail::SurfaceColour colour = textures->mean(polygon, c.data(), count);
        n.reflectance = colour.reflectance;
        n.emission = colour.emission;
        if (!world_light.empty()) n.emission += n.reflectance * world_light[std::size_t(n.patch)];
    }
    n.radiance = parent.radiance;  // a warm start for the next solve
    n.area = polygon_area(c, count);
    n.centre = Vec3(0.0f);
    for (int k = 0; k < count; ++k) n.centre += c[k] / float(count);
    n.longest_edge = longest_edge(c, count);
    for (int k = 0; k < count; ++k) n.radius = std::max(n.radius, glm::length(c[k] - n.centre));
}

bool Tree::subdivide(int32_t e, float finest) {
    std::lock_guard<std::mutex> lock(split_locks_[static_cast<std::size_t>(e) % split_locks_.size()]);
    Node& n = nodes[e];
    if (n.child_count > 0) return true;
    if (!can_split(n, finest)) return false;
    if (leaves_.fetch_add(3) + 3 > max_leaves_) {
        leaves_ -= 3;
        cap_reached_ = true;
        return false;
    }
    const auto& v = n.corners;
    std::array<std::array<int32_t, 4>, 4> children;
    if (n.is_triangle()) {
        const int32_t ab = midpoint(v[0], v[1]), bc = midpoint(v[1], v[2]), ca = midpoint(v[2], v[0]);
        children = {{{v[0], ab, ca, -1}, {ab, v[1], bc, -1}, {ca, bc, v[2], -1}, {ab, bc, ca, -1}}};
    } else {
        const int32_t ab = midpoint(v[0], v[1]), bc = midpoint(v[1], v[2]), cd = midpoint(v[2], v[3]),
                      da = midpoint(v[3], v[0]);
        // The centre is no neighbour's edge midpoint: a vertex of its own.
        const Vec3 centre = 0.25f * (vertices[v[0]] + vertices[v[1]] + vertices[v[2]] + vertices[v[3]]);
        const auto m = static_cast<int32_t>(vertices.push_back(centre) - vertices.begin());
        children = {{{v[0], ab, m, da}, {ab, v[1], bc, m}, {m, bc, v[2], cd}, {da, m, cd, v[3]}}};
    }
    const auto first = nodes.grow_by(4);
    const auto first_id = static_cast<int32_t>(first - nodes.begin());
    for (int k = 0; k < 4; ++k) {
        Node& child = nodes[first_id + k];
        child.parent = e;
        child.corners = children[k];
        fill_element(child, n);
    }
    n.first_child = first_id;
    n.child_count = 4;
    return true;
}

std::vector<int32_t> Tree::number_in_order(std::size_t first) {
    std::vector<int32_t> new_id(nodes.size() - first, -1);
    if (new_id.empty()) return new_id;
    // Nodes made since `first` are groups of four children (subdivide). Old split nodes whose
    // children are new come first, by id; then the new nodes that have children, as they get ids.
    std::vector<int32_t> parents;
    for (std::size_t n = 0; n < first; ++n)
        if (nodes[n].is_element() && nodes[n].child_count > 0 && std::size_t(nodes[n].first_child) >= first)
            parents.push_back(static_cast<int32_t>(n));
    auto next = static_cast<int32_t>(first);
    for (std::size_t q = 0; q < parents.size(); ++q) {
        const Node& parent = nodes[parents[q]];
        for (int k = 0; k < parent.child_count; ++k) {
            const int32_t c = parent.first_child + k;
            new_id[std::size_t(c) - first] = next++;
            if (nodes[c].child_count > 0) parents.push_back(c);
        }
    }
    auto renamed = [&](int32_t id) {
        return id >= 0 && std::size_t(id) >= first ? new_id[std::size_t(id) - first] : id;
    };
    tbb::parallel_for(std::size_t(0), nodes.size(), [&](std::size_t n) {
        Node& node = nodes[n];
        node.parent = renamed(node.parent);
        if (node.is_element()) node.first_child = renamed(node.first_child);
    });
    // Each node to its new place, cycle by cycle.
    std::vector<int32_t> place = new_id;
    for (std::size_t i = 0; i < place.size(); ++i)
        while (std::size_t(place[i]) != first + i) {
            const std::size_t j = std::size_t(place[i]) - first;
            std::swap(nodes[first + i], nodes[first + j]);
            std::swap(place[i], place[j]);
        }
    return new_id;
}

}  // namespace radiosity::hr
