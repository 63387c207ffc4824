/// @file box_tree.cpp
/// @brief Median-split construction of BoxTree (see box_tree.h).
#include "geometry/box_tree.h"

#include <algorithm>
#include <numeric>

namespace radiosity::detail {
namespace {

constexpr int32_t kLeafSize = 4;

}  // namespace

BoxTree::BoxTree(const std::vector<Box>& boxes) : boxes_(boxes), order_(boxes.size()) {
    if (boxes.empty()) return;
    std::iota(order_.begin(), order_.end(), 0);
    nodes_.reserve(boxes.size());  // leaves hold at least 2 boxes, so nodes < n
    nodes_.push_back({});
    build(0, 0, static_cast<int32_t>(boxes.size()));
}

/// Fills node `node` for order_[begin, end); children are allocated as a pair.
void BoxTree::build(int32_t node, int32_t begin, int32_t end) {
    Box box = boxes_[order_[begin]];
    glm::vec3 centre_lo(box.lo + box.hi), centre_hi = centre_lo;  // twice the centres: only their order matters
    for (int32_t k = begin; k < end; ++k) {
        const Box& b = boxes_[order_[k]];
        box.lo = glm::min(box.lo, b.lo);
        box.hi = glm::max(box.hi, b.hi);
        centre_lo = glm::min(centre_lo, b.lo + b.hi);
        centre_hi = glm::max(centre_hi, b.lo + b.hi);
    }
    if (end - begin <= kLeafSize) {
        nodes_[node] = {box, begin, end - begin};
        return;
    }
    const glm::vec3 spread = centre_hi - centre_lo;
    const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
    const int32_t middle = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end, [&](int32_t a, int32_t b) {
        return boxes_[a].lo[axis] + boxes_[a].hi[axis] < boxes_[b].lo[axis] + boxes_[b].hi[axis];
    });
    const auto left = static_cast<int32_t>(nodes_.size());
    nodes_[node] = {box, left, 0};
    nodes_.push_back({});
    nodes_.push_back({});
    build(left, begin, middle);
    build(left + 1, middle, end);
}

}  // namespace radiosity::detail
