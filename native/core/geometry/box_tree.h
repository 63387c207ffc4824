/// @file box_tree.h
/// @brief A bounding-volume hierarchy over axis-aligned boxes: which boxes overlap a query box.
///
/// Built by median splits on the longest axis of the box centres (O(n log n)). All overlapping
/// pairs are found by descending the tree against itself, which visits O(n + pairs) node pairs
/// whatever the mix of large and small boxes (a uniform grid does not).
#pragma once

#include <tbb/parallel_invoke.h>
#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace radiosity::detail {

struct Box {
    glm::vec3 lo, hi;
    bool overlaps(const Box& o) const {
        return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y && lo.z <= o.hi.z && o.lo.z <= hi.z;
    }
};

class BoxTree {
public:
    explicit BoxTree(const std::vector<Box>& boxes);

    /// Calls visit(a, b) once for every unordered pair of distinct overlapping boxes (closed boxes:
    /// touching counts), from several threads at once.
    template <class Visit>
    void visit_overlapping_pairs(Visit&& visit) const {
        if (!nodes_.empty()) pairs_within(0, visit, 0);
    }

private:
    struct Node {
        Box box;
        int32_t first;  ///< leaf: first index into order_; inner: its left child (right is first + 1)
        int32_t count;  ///< leaf: boxes in it; inner: 0
    };
    void build(int32_t node, int32_t begin, int32_t end);

    /// Subtrees this shallow are searched in parallel (2^kParallelDepth tasks).
    static constexpr int kParallelDepth = 6;

    template <class Visit>
    void pairs_within(int32_t node, Visit& visit, int depth) const {
        const Node& n = nodes_[node];
        if (n.count > 0) {
            for (int32_t k = n.first; k < n.first + n.count; ++k)
                for (int32_t l = k + 1; l < n.first + n.count; ++l)
                    if (boxes_[order_[k]].overlaps(boxes_[order_[l]])) visit(order_[k], order_[l]);
            return;
        }
        auto left = [&] { pairs_within(n.first, visit, depth + 1); };
        auto right = [&] { pairs_within(n.first + 1, visit, depth + 1); };
        auto across = [&] { pairs_across(n.first, n.first + 1, visit); };
        if (depth < kParallelDepth) {
            tbb::parallel_invoke(left, right, across);
        } else {
            left();
            right();
            across();
        }
    }

    /// Pairs with one box under node x and the other under node y (disjoint subtrees).
    template <class Visit>
    void pairs_across(int32_t x, int32_t y, Visit& visit) const {
        const Node &nx = nodes_[x], &ny = nodes_[y];
        if (!nx.box.overlaps(ny.box)) return;
        if (nx.count > 0 && ny.count > 0) {
            for (int32_t k = nx.first; k < nx.first + nx.count; ++k)
                for (int32_t l = ny.first; l < ny.first + ny.count; ++l)
                    if (boxes_[order_[k]].overlaps(boxes_[order_[l]])) visit(order_[k], order_[l]);
        } else if (ny.count > 0 || (nx.count == 0 && volume(nx.box) >= volume(ny.box))) {
            pairs_across(nx.first, y, visit);  // descend the inner node, the larger if both are
            pairs_across(nx.first + 1, y, visit);
        } else {
            pairs_across(x, ny.first, visit);
            pairs_across(x, ny.first + 1, visit);
        }
    }

    static float volume(const Box& b) {
        const glm::vec3 d = b.hi - b.lo;
        return d.x * d.y + d.y * d.z + d.z * d.x;  // half the surface: boxes may be flat
    }

    const std::vector<Box>& boxes_;
    std::vector<int32_t> order_;
    std::vector<Node> nodes_;
};

}  // namespace radiosity::detail
