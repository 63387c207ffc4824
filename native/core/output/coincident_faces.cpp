/// @file coincident_faces.cpp
/// @brief Elements of different polygons lying on each other (coincident_faces.h).
#include "output/coincident_faces.h"

#include "geometry/box_tree.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <utility>

namespace radiosity::detail {
namespace {

Box element_box(const Elements& elements, std::size_t e, float tolerance) {
    Box box{glm::vec3(elements.vertices[std::size_t(elements.corners[e][0])]), glm::vec3(0.0f)};
    box.hi = box.lo;
    for (int k = 1; k < elements.corner_count(e); ++k) {
        const glm::vec3 v = elements.vertices[std::size_t(elements.corners[e][k])];
        box.lo = glm::min(box.lo, v);
        box.hi = glm::max(box.hi, v);
    }
    box.lo -= glm::vec3(tolerance);
    box.hi += glm::vec3(tolerance);
    return box;
}

}  // namespace

CoincidentFaces::CoincidentFaces(const Elements& elements, float tolerance)
    : elements_(elements), partners_(elements.size()) {
    std::vector<Box> boxes;
    std::vector<int32_t> element;  // of each box: the fronts (a back side lies on its own front)
    for (std::size_t e = 0; e < elements.size(); ++e)
        if (!elements.is_back(e)) {
            boxes.push_back(element_box(elements, e, tolerance));
            element.push_back(int32_t(e));
        }
    std::mutex found;
    BoxTree(boxes).visit_overlapping_pairs([&](int32_t box_a, int32_t box_b) {
        const int32_t a = element[std::size_t(box_a)], b = element[std::size_t(box_b)];
        const std::size_t i = std::size_t(a), j = std::size_t(b);
        if (elements.polygon[i] == elements.polygon[j] ||
            glm::dot(elements.normal[i], elements.normal[j]) < kParallelCosine ||
            std::abs(glm::dot(elements.centre[j] - elements.centre[i], elements.normal[i])) > tolerance)
            return;
        const std::lock_guard<std::mutex> lock(found);
        partners_[i].push_back(b);
        partners_[j].push_back(a);
    });
    for (std::vector<int32_t>& partners : partners_) std::sort(partners.begin(), partners.end());
}

bool CoincidentFaces::covered(const Vec3& x, std::size_t e) const {
    const std::vector<int32_t>& partners = partners_[e];
    if (partners.empty()) return false;
    // A quarter of a float's spacing at x's largest coordinate.
    const double on_edge = 0x1p-25 * double(std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)}));
    return std::any_of(partners.begin(), partners.end(), [&](int32_t h) {
        glm::dvec3 inwards(0.0);
        if (!inside(glm::dvec3(x), std::size_t(h), on_edge, &inwards)) return false;
        if (inwards == glm::dvec3(0.0)) return true;
        // On an edge of h: covered where e goes on across that edge, so that h lies on e there (an
        // overlap), not where e ends at it (a neighbour in the plane).
        const glm::dvec3 across = glm::dvec3(x) + 2.0 * on_edge * glm::normalize(inwards);
        return inside(across, std::size_t(h), 0.0) && inside(across, e, 0.0);
    });
}

std::size_t CoincidentFaces::covered_elements() const {
    return std::size_t(std::count_if(partners_.begin(), partners_.end(), [](const auto& p) { return !p.empty(); }));
}

bool CoincidentFaces::inside(const glm::dvec3& p, std::size_t h, double on_edge, glm::dvec3* inwards) const {
    const glm::dvec3 n(elements_.normal[h]);
    const int count = elements_.corner_count(h);
    for (int k = 0; k < count; ++k) {
        const glm::dvec3 a(elements_.vertices[std::size_t(elements_.corners[h][k])]);
        const glm::dvec3 b(elements_.vertices[std::size_t(elements_.corners[h][(k + 1) % count])]);
        const double edge = glm::length(b - a);
        const double side = glm::dot(glm::cross(b - a, p - a), n);
        if (side > 0.0) continue;
        if (!(side > -on_edge * edge) || inwards == nullptr) return false;
        *inwards += glm::cross(n, b - a) / edge;
    }
    return true;
}

}  // namespace radiosity::detail
