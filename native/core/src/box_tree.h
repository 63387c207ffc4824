/// @file box_tree.h
/// @brief A bounding-volume hierarchy over axis-aligned boxes: which boxes overlap a query box.
///
/// Built by median splits on the longest axis of the box centres (O(n log n)); a query visits
/// O(log n + overlaps) nodes whatever the mix of large and small boxes, which a uniform grid does not.
#pragma once

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

    /// Calls visit(index) for every box that overlaps `query` (closed boxes: touching counts).
    template <class Visit>
    void visit_overlapping(const Box& query, Visit&& visit) const {
        if (nodes_.empty()) return;
        int32_t stack[64];  // depth is log2(n / leaf size) < 64
        int depth = 0;
        stack[depth++] = 0;
        while (depth > 0) {
            const Node& node = nodes_[stack[--depth]];
            if (!node.box.overlaps(query)) continue;
            if (node.count > 0) {
                for (int32_t k = node.first; k < node.first + node.count; ++k)
                    if (boxes_[order_[k]].overlaps(query)) visit(order_[k]);
            } else {
                stack[depth++] = node.first;
                stack[depth++] = node.first + 1;
            }
        }
    }

private:
    struct Node {
        Box box;
        int32_t first;  ///< leaf: first index into order_; inner: its left child (right is first + 1)
        int32_t count;  ///< leaf: boxes in it; inner: 0
    };
    void build(int32_t node, int32_t begin, int32_t end);

    const std::vector<Box>& boxes_;
    std::vector<int32_t> order_;
    std::vector<Node> nodes_;
};

}  // namespace radiosity::detail
