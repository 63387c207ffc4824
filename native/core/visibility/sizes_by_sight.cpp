/// @file sizes_by_sight.cpp
/// @brief Element sizes from the distance each polygon sees other surfaces at (sizes_by_sight.h).
#include "visibility/sizes_by_sight.h"

#include "common/parallel_rows.h"
#include "visibility/element_rays.h"
#include "visibility/shadow_ray.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace radiosity {
namespace {

constexpr std::size_t kElementsPerPolygon = 8;
constexpr double kLargest = 0.25;      ///< of the element size: distances beyond it keep the element size
constexpr double kMoreElements = 0.5;  ///< of the elements' count: what the cuts may add,
constexpr double kMoreAtLeast = 2048;  ///< or this many in a small scene

double longest_edge(const Elements& elements, std::size_t e) {
    double longest = 0.0;
    const int count = elements.corner_count(e);
    for (int k = 0; k < count; ++k)
        longest =
            std::max(longest, double(glm::length(elements.vertices[std::size_t(elements.corners[e][(k + 1) % count])] -
                                                 elements.vertices[std::size_t(elements.corners[e][k])])));
    return longest;
}

/// The harmonic mean of the distances at which element e's rays meet fronts; 0 where none does
/// or where most of them meet a back face nearer than the element's size (it lies under other
/// geometry: a level's floor running on under a wall).
double harmonic_distance(const Elements& elements, std::size_t e, const hr::Visibility& rays) {
    const float near = std::sqrt(elements.area[e]);
    double inverse = 0.0;
    int fronts = 0, backs = 0;
    detail::element_rays(elements, e, elements.normal[e], rays,
                         [&](const Vec3& direction, const hr::Visibility::Hit& hit) {
                             if (glm::dot(direction, elements.normal[std::size_t(hit.patch)]) >= 0.0f) {
                                 backs += hit.distance < near;
                                 return;
                             }
                             inverse += 1.0 / double(hit.distance);
                             ++fronts;
                         });
    if (2 * backs > detail::kElementRays || fronts == 0) return 0.0;
    return double(fronts) / inverse;
}

/// The median over up to kElementsPerPolygon of a polygon's elements of their harmonic_distance (0:
/// none counts): a polygon narrow only beside a pillar is not narrow.
double polygon_distance(const Elements& elements, const std::vector<int32_t>& polygon, const hr::Visibility& rays) {
    std::vector<double> distances;
    detail::spread_elements(polygon, kElementsPerPolygon, [&](std::size_t e) {
        const double distance = harmonic_distance(elements, e, rays);
        if (distance > 0.0) distances.push_back(distance);
    });
    if (distances.empty()) return 0.0;
    std::nth_element(distances.begin(), distances.begin() + distances.size() / 2, distances.end());
    return distances[distances.size() / 2];
}

/// The least size the polygons may be cut to, from `smallest` up, so that the elements they gain (a
/// polygon's area over its size squared, less the elements it has) stay within kMoreElements of the
/// elements' count (kMoreAtLeast in a small scene): a slab 5 mm over a floor would otherwise be cut
/// into 5 mm elements, which the near-field correction (transport/near_field.h) serves at a
/// fraction of the cost.
double least_size(const Elements& elements, const std::vector<std::vector<int32_t>>& of_polygon,
                  const std::vector<double>& distance, double smallest, double largest) {
    std::vector<double> area(of_polygon.size(), 0.0);
    for (std::size_t p = 0; p < of_polygon.size(); ++p)
        for (const int32_t e : of_polygon[p]) area[p] += double(elements.area[std::size_t(e)]);
    auto gained = [&](double floor) {
        double more = 0.0;
        for (std::size_t p = 0; p < of_polygon.size(); ++p) {
            const double size = std::max(distance[p], floor);
            if (distance[p] > 0.0 && size < largest)
                more += std::max(0.0, area[p] / (size * size) - double(of_polygon[p].size()));
        }
        return more;
    };
    const double budget = std::max(kMoreElements * double(elements.size()), kMoreAtLeast);
    if (gained(smallest) <= budget) return smallest;
    double lo = smallest, hi = largest;
    for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (gained(mid) <= budget ? hi : lo) = mid;
    }
    return hi;
}

}  // namespace

std::vector<float> sizes_by_sight(const Elements& elements, std::size_t polygons, float element_size) {
    std::vector<float> sizes(polygons, 0.0f);
    if (!(element_size > 0.0f) || elements.size() == 0) return sizes;
    const double smallest = double(element_size) / 8.0;
    std::vector<std::vector<int32_t>> of_polygon(polygons);
    std::vector<uint8_t> worth(polygons, 0);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const std::size_t p = std::size_t(elements.polygon[e]);
        if (elements.has_twin(e) || !elements.blocks(e) || !(elements.area[e] > 0.0f)) {
            worth[p] = 2;  // an emitter's or a lamp's: left as it is
            continue;
        }
        of_polygon[p].push_back(int32_t(e));
        if (worth[p] == 0 && longest_edge(elements, e) > smallest) worth[p] = 1;
    }
    const hr::Visibility rays(elements.vertices, detail::blocking_corners(elements), scene_diagonal(elements.vertices));
    std::vector<double> distance(polygons, 0.0);
    detail::parallel_rows("element sizes", polygons, 16, 0, {}, [&](std::size_t p) {
        if (worth[p] == 1) distance[p] = polygon_distance(elements, of_polygon[p], rays);
        return true;
    });
    const double floor = least_size(elements, of_polygon, distance, smallest, kLargest * double(element_size));
    for (std::size_t p = 0; p < polygons; ++p)
        if (distance[p] > 0.0 && std::max(distance[p], floor) < kLargest * double(element_size))
            sizes[p] = float(std::max(distance[p], floor));
    return sizes;
}

bool any_size(const std::vector<float>& sizes) {
    return std::any_of(sizes.begin(), sizes.end(), [](float size) { return size > 0.0f; });
}

}  // namespace radiosity
