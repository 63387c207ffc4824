/// @file open_backs.cpp
/// @brief The faces whose back side looks into the scene (open_backs.h).
#include "visibility/open_backs.h"

#include "common/parallel_rows.h"
#include "visibility/element_rays.h"
#include "visibility/shadow_ray.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <memory>

namespace radiosity {
namespace {

constexpr std::size_t kElementsPerPolygon = 8;
constexpr double kOpenShare = 1.0 / 8.0;  ///< of the rays meeting fronts: the back is open
constexpr int kEnclosedBacks = 15;        ///< of an element's 16 rays meeting back faces: it is enclosed

/// Whether element `hit` shows its front to a ray along `direction`.
bool faces(const Elements& elements, const Vec3& direction, std::size_t hit) {
    return glm::dot(direction, elements.normal[hit]) < 0.0f;
}

/// Whether an element is enclosed: all its rays but one meet back faces, so it lies inside
/// something (the floor under a box standing on it) and no light reaches it. A floor under a bridge
/// sees out past it. Found for the elements a back's rays meet, once each, from any thread.
class Enclosure {
public:
    Enclosure(const Elements& elements, const hr::Visibility& rays)
        : elements_(elements), rays_(rays), state_(new std::atomic<uint8_t>[elements.size()]()) {}

    bool enclosed(std::size_t e) const {
        uint8_t state = state_[e].load(std::memory_order_relaxed);
        if (state == kUnknown) {
            int backs = 0;
            detail::element_rays(elements_, e, elements_.normal[e], rays_,
                                 [&](const Vec3& direction, const hr::Visibility::Hit& hit) {
                                     backs += !faces(elements_, direction, std::size_t(hit.patch));
                                 });
            state = backs >= kEnclosedBacks ? kEnclosed : kOpen;
            state_[e].store(state, std::memory_order_relaxed);  // the same from every thread
        }
        return state == kEnclosed;
    }

private:
    static constexpr uint8_t kUnknown = 0, kOpen = 1, kEnclosed = 2;
    const Elements& elements_;
    const hr::Visibility& rays_;
    std::unique_ptr<std::atomic<uint8_t>[]> state_;
};

/// How many of element e's rays from its back meet the front of a surface that is not enclosed.
int fronts_behind(const Elements& elements, std::size_t e, const hr::Visibility& rays, const Enclosure& enclosure) {
    int fronts = 0;
    detail::element_rays(elements, e, -elements.normal[e], rays,
                         [&](const Vec3& direction, const hr::Visibility::Hit& hit) {
                             const std::size_t h = std::size_t(hit.patch);
                             fronts += faces(elements, direction, h) && !enclosure.enclosed(h);
                         });
    return fronts;
}

}  // namespace

std::vector<uint8_t> open_backs(const Elements& elements, std::size_t polygons) {
    std::vector<uint8_t> open(polygons, 0);
    if (elements.size() == 0) return open;
    std::vector<std::vector<int32_t>> of_polygon(polygons);
    std::vector<uint8_t> skip(polygons, 0);
    for (std::size_t e = 0; e < elements.size(); ++e) {
        const std::size_t p = std::size_t(elements.polygon[e]);
        if (elements.has_twin(e) || !elements.blocks(e) || max_channel(elements.emission[e]) > 0.0)
            skip[p] = 1;
        else if (elements.area[e] > 0.0f)
            of_polygon[p].push_back(int32_t(e));
    }
    const hr::Visibility rays(elements.vertices, detail::blocking_corners(elements), scene_diagonal(elements.vertices));
    const Enclosure enclosure(elements, rays);
    detail::parallel_rows("open backs", polygons, 16, 0, {}, [&](std::size_t p) {
        if (skip[p] || of_polygon[p].empty()) return true;
        int fronts = 0, cast = 0;
        detail::spread_elements(of_polygon[p], kElementsPerPolygon, [&](std::size_t e) {
            fronts += fronts_behind(elements, e, rays, enclosure);
            cast += detail::kElementRays;
        });
        open[p] = double(fronts) >= kOpenShare * double(cast);
        return true;
    });
    return open;
}

bool any_open(const std::vector<uint8_t>& open) {
    return std::any_of(open.begin(), open.end(), [](uint8_t o) { return o != 0; });
}

}  // namespace radiosity
