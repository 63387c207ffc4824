/// @file lamp_detail.cpp
/// @brief Leaves split for the lamps' light, and that light at the output's corners (hierarchy/lamp_detail.h).
#include "hierarchy/lamp_detail.h"

#include "common/parallel_rows.h"
#include "transport/lamp_points.h"

#include <tbb/concurrent_vector.h>
#include <glm/common.hpp>

#include <atomic>
#include <cmath>

namespace radiosity::hr {
namespace {

/// The lamps' light gathered at `x` (E / pi: radiance per unit reflectance).
Rgb lamp_light_at(const Lights& lights, const Visibility& visibility, const Vec3& x, const Vec3& normal) {
    return detail::lamp_irradiance(lights, visibility, x, normal) / M_PI;
}

using CornerWeights = std::array<float, 4>;

/// Points inside an element as weights of its corners: the centres of a 4 x 4 grid of a quad
/// (bilinear), the centroids of the 16 equal triangles of a triangle cut 4 ways per edge.
const std::vector<CornerWeights>& grid_weights(bool triangle) {
    static const std::vector<CornerWeights> quad = [] {
        std::vector<CornerWeights> w;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) {
                const float u = (i + 0.5f) / 4, v = (j + 0.5f) / 4;
                w.push_back({(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v});
            }
        return w;
    }();
    static const std::vector<CornerWeights> tri = [] {
        std::vector<CornerWeights> w;
        auto add = [&](float i, float j) { w.push_back({1 - (i + j) / 4, i / 4, j / 4, 0.0f}); };
        for (int i = 0; i < 4; ++i)
            for (int j = 0; i + j < 4; ++j) {
                add(i + 1.0f / 3, j + 1.0f / 3);
                if (i + j + 1 < 4) add(i + 2.0f / 3, j + 2.0f / 3);
            }
        return w;
    }();
    return triangle ? tri : quad;
}

class LampSplitter {
public:
    LampSplitter(Tree& tree, const Visibility& visibility, double threshold, float finest)
        : tree_(tree), visibility_(visibility), threshold_(threshold), finest_(finest) {}

    struct Examined {
        bool departs = false;
        Rgb mean{0.0};  ///< lamp light (E / pi) over the grid: the element's mean
    };

    /// The lamp light over leaf `id` against what its corners show.
    Examined examine(int32_t id) const {
        const Node& n = tree_.nodes[id];
        std::array<Vec3, 4> c;
        const int count = element_corners(tree_, n, c);
        std::array<Rgb, 4> at_corner{};
        for (int k = 0; k < count; ++k) at_corner[k] = gathered(n, inside(c[k], n.centre));
        Examined e;
        const auto& grid = grid_weights(count == 3);
        const double rho = max_channel(n.reflectance);
        for (const CornerWeights& w : grid) {
            Vec3 p(0.0f);
            Rgb shown(0.0);
            for (int k = 0; k < count; ++k) {
                p += w[k] * c[k];
                shown += double(w[k]) * at_corner[k];
            }
            const Rgb at = gathered(n, p);
            e.mean += at / double(grid.size());
            e.departs = e.departs || rho * max_channel(glm::abs(at - shown)) > threshold_;
        }
        return e;
    }

    /// Splits leaf `id` (lamp light `lamp`, examined as `e`) if its lamp light departs from its
    /// corners' interpolation, then its children in turn, each of which takes its own lamp light
    /// in place of its share of `lamp`.
    void split(int32_t id, const Rgb& lamp, const Examined& e) {
        const Node& n = tree_.nodes[id];
        if (!e.departs || !tree_.can_split(n, finest_) || !tree_.subdivide(id, finest_)) return;
        ++splits;
        // The light n gathered besides the lamps', per unit reflectance: its radiance is its
        // emission plus its reflectance times the light gathered.
        Rgb rest(0.0);
        for (int ch = 0; ch < 3; ++ch)
            if (n.reflectance[ch] > 0.0) rest[ch] = (n.radiance[ch] - n.emission[ch]) / n.reflectance[ch] - lamp[ch];
        for (int k = 0; k < n.child_count; ++k) {
            const int32_t c = child(n, k);
            const Examined own = examine(c);
            own_lamp_light.push_back({c, own.mean});
            Node& below = tree_.nodes[c];
            below.radiance = below.emission + below.reflectance * (rest + own.mean);
            split(c, own.mean, own);
        }
    }

    std::atomic<std::size_t> splits{0};
    /// Split children and their own lamp light (gathered, per unit reflectance).
    tbb::concurrent_vector<std::pair<int32_t, Rgb>> own_lamp_light;

private:
    Rgb gathered(const Node& n, const Vec3& x) const { return lamp_light_at(tree_.lights, visibility_, x, n.normal); }

    Tree& tree_;
    const Visibility& visibility_;
    double threshold_;
    float finest_;
};

}  // namespace

std::size_t split_for_lamp_light(Tree& tree, const Visibility& visibility, double threshold, float finest,
                                 std::vector<Rgb>& lamp_light, const ProgressFn& progress) {
    if (tree.lights.empty()) return 0;
    std::vector<int32_t> leaves;
    for (std::size_t n = 0; n < tree.nodes.size(); ++n) {
        const Node& node = tree.nodes[n];
        if (node.is_element() && node.is_leaf() && max_channel(node.reflectance) > 0.0 && tree.can_split(node, finest))
            leaves.push_back(static_cast<int32_t>(n));
    }
    const std::size_t first_new = tree.nodes.size();
    LampSplitter splitter(tree, visibility, threshold, finest);
    detail::parallel_rows("output", leaves.size(), 16, 0, progress, [&](std::size_t i) {
        splitter.split(leaves[i], lamp_light[leaves[i]], splitter.examine(leaves[i]));
        return true;
    });
    const std::vector<int32_t> new_id = tree.number_in_order(first_new);
    lamp_light.resize(tree.nodes.size(), Rgb(0.0));
    for (const auto& [node, light] : splitter.own_lamp_light) lamp_light[new_id[std::size_t(node) - first_new]] = light;
    return splitter.splits;
}

std::vector<Rgb> lamp_light_at_corners(const Elements& mesh, const Lights& lights, const Visibility& visibility,
                                       const ProgressFn& progress) {
    std::vector<Rgb> light(4 * mesh.size(), Rgb(0.0));
    if (lights.empty()) return light;
    detail::parallel_rows("output", mesh.size(), 256, 0, progress, [&](std::size_t e) {
        if (!(max_channel(mesh.reflectance[e]) > 0.0)) return true;
        for (int k = 0; k < (mesh.is_triangle(e) ? 3 : 4); ++k) {
            const Vec3 x = inside(mesh.vertices[mesh.corners[e][k]], mesh.centre[e]);
            light[4 * e + k] = mesh.reflectance[e] * lamp_light_at(lights, visibility, x, mesh.normal[e]);
        }
        return true;
    });
    return light;
}

}  // namespace radiosity::hr
