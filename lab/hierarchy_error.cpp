#include "hierarchy_error.h"

#include "hierarchy_locate.h"

#include "hierarchy/hierarchy.h"
#include "output/interpolation.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

namespace radiosity::charts {
namespace {

/// One polygon's elements in its plane, bucketed on a grid for lookup.
class PolygonLocator {
public:
    PolygonLocator(const Elements& mesh, std::vector<int32_t> elements) : mesh_(mesh), elements_(std::move(elements)) {
        const Vec3 n = mesh.normal[elements_.front()];
        u_ = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
        v_ = glm::cross(n, u_);
        lo_ = Vec2(std::numeric_limits<double>::max());
        Vec2 hi(-std::numeric_limits<double>::max());
        for (int32_t e : elements_)
            for (int k = 0; k < corner_count(e); ++k) {
                lo_ = glm::min(lo_, project(mesh.vertices[mesh.corners[e][k]]));
                hi = glm::max(hi, project(mesh.vertices[mesh.corners[e][k]]));
            }
        size_ = std::max<int>(1, int(std::sqrt(double(elements_.size()))));
        cell_ = glm::max((hi - lo_) / double(size_), Vec2(1e-9));
        cells_.resize(std::size_t(size_) * size_);
        for (std::size_t i = 0; i < elements_.size(); ++i) {
            Vec2 a(std::numeric_limits<double>::max()), b(-std::numeric_limits<double>::max());
            for (int k = 0; k < corner_count(elements_[i]); ++k) {
                a = glm::min(a, project(mesh.vertices[mesh.corners[elements_[i]][k]]));
                b = glm::max(b, project(mesh.vertices[mesh.corners[elements_[i]][k]]));
            }
            const auto [x0, y0] = cell_of(a);
            const auto [x1, y1] = cell_of(b);
            for (int x = x0; x <= x1; ++x)
                for (int y = y0; y <= y1; ++y) cells_[std::size_t(y) * size_ + x].push_back(int32_t(i));
        }
    }

    /// The colour at `p`; `located` false when no element holds it (the nearest in its cell is used).
    Rgb colour(const Vec3& point, const std::vector<Rgb>& element_corner, bool& located) const {
        const Vec2 p = project(point);
        const auto [x, y] = cell_of(p);
        Location best;
        int32_t best_element = -1;
        for (int32_t i : cells_[std::size_t(y) * size_ + x]) {
            const int32_t e = elements_[i];
            Vec2 c[4];
            for (int k = 0; k < corner_count(e); ++k) c[k] = project(mesh_.vertices[mesh_.corners[e][k]]);
            const Location l = corner_count(e) == 3 ? locate_triangle(c, p) : locate_quad(c, p);
            if (l.outside < best.outside) {
                best = l;
                best_element = e;
            }
            if (best.outside == 0.0) break;
        }
        located = best.outside < 1e-3;
        Rgb colour(0.0);
        if (best_element < 0) return colour;
        for (int k = 0; k < corner_count(best_element); ++k)
            colour += best.weight[k] * element_corner[4 * std::size_t(best_element) + k];
        return colour;
    }

private:
    int corner_count(int32_t e) const { return mesh_.is_triangle(e) ? 3 : 4; }
    Vec2 project(const Vec3& p) const { return Vec2(glm::dot(p, u_), glm::dot(p, v_)); }
    std::pair<int, int> cell_of(Vec2 p) const {
        const Vec2 c = (p - lo_) / cell_;
        return {std::clamp(int(c.x), 0, size_ - 1), std::clamp(int(c.y), 0, size_ - 1)};
    }

    const Elements& mesh_;
    std::vector<int32_t> elements_;
    Vec3 u_, v_;
    Vec2 lo_, cell_;
    int size_ = 1;
    std::vector<std::vector<int32_t>> cells_;
};

}  // namespace

Samples sample_polygons(const SceneInput& input, float spacing) {
    Samples s;
    auto corner = [&](int32_t c) {
        const float* p = input.positions + 3 * std::size_t(input.corner_vertices[c]);
        return Vec3(p[0], p[1], p[2]);
    };
    for (std::size_t f = 0; f < input.face_count; ++f) {
        const float* emitted = input.emission + 3 * f;
        if (emitted[0] > 0.0f || emitted[1] > 0.0f || emitted[2] > 0.0f) continue;
        const int32_t first = input.face_offsets[f], end = input.face_offsets[f + 1];
        const Vec3 o = corner(first);
        glm::dvec3 newell(0.0);
        for (int32_t k = first; k < end; ++k) {
            const glm::dvec3 a(corner(k)), b(corner(k + 1 < end ? k + 1 : first));
            newell += glm::cross(a, b);
        }
        const Vec3 normal(glm::normalize(newell));
        const float* rho = input.reflectance + 3 * f;
        for (int32_t k = first + 1; k + 1 < end; ++k) {
            const Vec3 a = corner(k) - o, b = corner(k + 1) - o;
            const float longest = std::max({glm::length(a), glm::length(b), glm::length(b - a)});
            const int n = std::max(1, int(std::ceil(longest / spacing)));
            const double weight = 0.5 * glm::length(glm::cross(a, b)) / (double(n) * n);
            auto add = [&](double i, double j) {
                s.point.push_back(o + float(i / n) * a + float(j / n) * b);
                s.weight.push_back(weight);
                s.polygon.push_back(int32_t(f));
                s.normal.push_back(normal);
                s.reflectance.push_back(Rgb(rho[0], rho[1], rho[2]));
            };
            for (int i = 0; i < n; ++i)
                for (int j = 0; i + j < n; ++j) {
                    add(i + 1.0 / 3, j + 1.0 / 3);                     // upward sub-triangle
                    if (i + j + 1 < n) add(i + 2.0 / 3, j + 2.0 / 3);  // downward sub-triangle
                }
        }
    }
    return s;
}

std::vector<Rgb> colours_at(const Samples& samples, const Elements& mesh, const std::vector<Rgb>& element_corner,
                            std::size_t& unlocated) {
    std::vector<std::vector<int32_t>> by_polygon;
    for (std::size_t e = 0; e < mesh.size(); ++e) {
        const auto p = std::size_t(mesh.polygon[e]);
        if (p >= by_polygon.size()) by_polygon.resize(p + 1);
        by_polygon[p].push_back(int32_t(e));
    }
    std::vector<std::unique_ptr<PolygonLocator>> locators(by_polygon.size());
    for (std::size_t p = 0; p < by_polygon.size(); ++p)
        if (!by_polygon[p].empty()) locators[p] = std::make_unique<PolygonLocator>(mesh, by_polygon[p]);
    std::vector<Rgb> colours(samples.point.size(), Rgb(0.0));
    unlocated = 0;
    for (std::size_t i = 0; i < samples.point.size(); ++i) {
        const auto p = std::size_t(samples.polygon[i]);
        bool located = false;
        if (p < locators.size() && locators[p])
            colours[i] = locators[p]->colour(samples.point[i], element_corner, located);
        unlocated += !located;
    }
    return colours;
}

std::vector<Rgb> lamp_light_at(const Samples& samples, const Elements& surfaces, const Lights& lights) {
    std::vector<Rgb> light(samples.point.size(), Rgb(0.0));
    if (lights.empty()) return light;
    const std::vector<Rgb> irradiance = lamp_irradiance_at(surfaces, lights, samples.point, samples.normal);
    for (std::size_t i = 0; i < light.size(); ++i) light[i] = samples.reflectance[i] * irradiance[i] / M_PI;
    return light;
}

std::vector<Rgb> reference_colours(const Samples& samples, const Elements& mesh, const std::vector<Rgb>& radiance,
                                   const int32_t* material, const std::vector<Rgb>& lamp_light,
                                   std::size_t& unlocated) {
    std::vector<Rgb> rest(mesh.size());
    for (std::size_t e = 0; e < mesh.size(); ++e) rest[e] = radiance[e] - mesh.emission[e];
    const CornerColors corners = interpolate_corners(mesh, rest, material, HierarchySettings().hard_edge_angle);
    std::vector<Rgb> colours = colours_at(samples, mesh, corners.element_corner, unlocated);
    for (std::size_t i = 0; i < colours.size(); ++i) colours[i] += lamp_light[i];
    return colours;
}

ColourError colour_error(const Samples& samples, const std::vector<Rgb>& got, const std::vector<Rgb>& reference) {
    double area = 0.0, mean = 0.0, squared = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < samples.point.size(); ++i) {
        const Rgb d = got[i] - reference[i];
        const double d2 = glm::dot(d, d) / 3.0;
        area += samples.weight[i];
        mean += samples.weight[i] * (reference[i].r + reference[i].g + reference[i].b) / 3.0;
        squared += samples.weight[i] * d2;
        largest = std::max(largest, d2);
    }
    mean /= area;
    return {std::sqrt(squared / area) / mean, std::sqrt(largest) / mean};
}

}  // namespace radiosity::charts
