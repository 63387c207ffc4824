/// @file emitter_groups.cpp
/// @brief Emitting elements grouped by polygon side, and their exact light at a point (emitter_groups.h).
#include "output/emitter_groups.h"

#include "geometry/polygon_geometry.h"
#include "transport/near_field.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <utility>

namespace radiosity::detail {
namespace {

/// Emitters of one polygon whose normals agree this well lie on one side of it.
constexpr double kSamePlane = 0.9999;
/// An emitter of another polygon joins a run when its corners lie this close to the run's plane,
/// relative to the emitter's size (besides its normal and its radiance: run_takes).
constexpr double kPlaneGap = 1e-4;
/// Two outline edges meeting at a turn below this sine are one straight edge: float corners of a
/// subdivided face lie on its edge to about 1e-7 of the coordinates, a few 1e-6 of a small face's edge.
constexpr double kStraightSine = 1e-4;

/// A corner by its bits: neighbouring faces' elements meet at bit-identical points.
using PointKey = std::array<float, 3>;
PointKey key_of(const Vec3& p) { return {p.x + 0.0f, p.y + 0.0f, p.z + 0.0f}; }

/// Whether emitter `source` lies on the run's side: of its polygon and plane, or of another polygon
/// in the same plane emitting the same radiance and meeting the run at a corner (a tessellated
/// emitter, whose faces are polygons of their own).
bool run_takes(const EmitterRun& run, const Emitter& first, const Emitter& source, const std::set<PointKey>& corners) {
    if (glm::dot(first.normal, source.normal) < kSamePlane) return false;
    if (first.polygon_index == source.polygon_index) return true;
    if (source.radiance != first.radiance) return false;
    const double gap = kPlaneGap * std::sqrt(source.area);
    bool touches = false;
    for (int k = 0; k < source.count; ++k) {
        if (std::abs(glm::dot(run.normal, source.polygon[k] - run.point)) > gap) return false;
        touches = touches || corners.count(key_of(Vec3(source.polygon[k]))) > 0;
    }
    return touches;
}

glm::dvec3 point_of(const PointKey& p) { return glm::dvec3(p[0], p[1], p[2]); }

/// Directed edges as straight runs: where just one edge arrives at a point, just one leaves, and
/// the two go on in a straight line (a tessellated emitter's outline, a piece per face), the point
/// is no corner and the two pieces are one edge (the contour integral is additive along a segment).
std::vector<std::array<glm::dvec3, 2>> straight_runs(const std::set<std::pair<PointKey, PointKey>>& edges) {
    std::map<PointKey, std::vector<PointKey>> leaving, arriving;
    for (const auto& [a, b] : edges) {
        leaving[a].push_back(b);
        arriving[b].push_back(a);
    }
    // The point after b when the edge from a to b goes straight on through it.
    auto straight_on = [&](const PointKey& a, const PointKey& b) -> std::optional<PointKey> {
        const std::vector<PointKey>& in = arriving[b];
        const std::vector<PointKey>& out = leaving[b];
        if (in.size() != 1 || out.size() != 1 || !straight(point_of(a), point_of(b), point_of(out[0]), kStraightSine))
            return std::nullopt;
        return out[0];
    };
    std::vector<std::array<glm::dvec3, 2>> runs;
    for (const auto& [a, b] : edges) {
        const std::vector<PointKey>& in = arriving[a];
        if (in.size() == 1 && straight_on(in[0], a)) continue;  // inside a run that starts before a
        PointKey from = a, end = b;
        while (const std::optional<PointKey> next = straight_on(from, end)) {
            from = end;
            end = *next;
        }
        runs.push_back({point_of(a), point_of(end)});
    }
    return runs;
}

/// The run's outline, centre and radius: the directed edges of its elements whose reverse no other
/// element of the run has (the tiles' shared edges cancel in the contour integral), straight runs of
/// them joined.
void outline(const Elements& elements, const std::vector<Emitter>& emitters, EmitterRun& run) {
    std::set<std::pair<PointKey, PointKey>> edges;
    std::size_t vertex_count = 0;
    for (std::size_t i = run.first; i < run.last; ++i) {
        const std::size_t e = std::size_t(emitters[i].element);
        const int count = elements.corner_count(e);
        for (int k = 0; k < count; ++k) {
            const Vec3 &a = elements.vertices[elements.corners[e][k]],
                       &b = elements.vertices[elements.corners[e][(k + 1) % count]];
            if (!edges.erase({key_of(b), key_of(a)})) edges.insert({key_of(a), key_of(b)});
            run.centre += glm::dvec3(a);
            ++vertex_count;
        }
    }
    run.centre /= double(std::max<std::size_t>(vertex_count, 1));
    run.area_before.assign(1, 0.0);
    for (std::size_t i = run.first; i < run.last; ++i)
        run.area_before.push_back(run.area_before.back() + emitters[i].area);
    for (const auto& [a, b] : edges)
        run.radius =
            std::max({run.radius, glm::length(point_of(a) - run.centre), glm::length(point_of(b) - run.centre)});
    run.outline = straight_runs(edges);
}

}  // namespace

std::vector<Emitter> emitting_elements(const Elements& elements, const std::vector<Rgb>& emitted) {
    std::vector<Emitter> emitters;
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (!(max_channel(emitted[e]) > 0.0) || !(elements.area[e] > 0.0f)) continue;
        Emitter source{int32_t(e),
                       {},
                       elements.corner_count(e),
                       glm::dvec3(elements.normal[e]),
                       emitted[e],
                       elements.polygon[e],
                       double(elements.area[e])};
        for (int k = 0; k < source.count; ++k)
            source.polygon[k] = glm::dvec3(elements.vertices[elements.corners[e][k]]);
        emitters.push_back(source);
    }
    return emitters;
}

std::vector<EmitterRun> emitter_runs(const Elements& elements, const std::vector<Emitter>& emitters) {
    std::vector<EmitterRun> runs;
    std::set<PointKey> corners;  // the last run's
    for (std::size_t i = 0; i < emitters.size(); ++i) {
        const Emitter& source = emitters[i];
        if (runs.empty() || !run_takes(runs.back(), emitters[runs.back().first], source, corners)) {
            EmitterRun run;
            run.first = i;
            run.normal = source.normal;
            run.point = source.polygon[0];
            runs.push_back(run);
            corners.clear();
        }
        EmitterRun& run = runs.back();
        run.last = i + 1;
        run.uniform = run.uniform && source.radiance == emitters[run.first].radiance;
        for (int k = 0; k < source.count; ++k) corners.insert(key_of(Vec3(source.polygon[k])));
    }
    for (EmitterRun& run : runs) outline(elements, emitters, run);
    return runs;
}

EmitterGroups emitter_groups(const std::vector<Emitter>& emitters, const std::vector<EmitterRun>& runs,
                             const glm::dvec3& x, const glm::dvec3& n) {
    EmitterGroups seen;
    seen.faces.assign(emitters.size(), 0);
    for (const EmitterRun& run : runs) {
        EmitterGroup group;
        group.first = run.first;
        group.last = run.last;
        group.run = std::size_t(&run - runs.data());
        // Behind the run's plane, or in it, nothing of it faces x.
        if (glm::dot(run.normal, x - run.point) > 0.0) {
            if (run.uniform && glm::dot(n, run.centre - x) > run.radius) {  // wholly above x's tangent plane
                double sum = 0.0;
                for (const auto& edge : run.outline) sum += contour_term(n, edge[0] - x, edge[1] - x);
                group.light = emitters[run.first].radiance * (std::abs(sum) / (2.0 * M_PI));
                group.area = run.area_before.back();
                group.whole = true;
            } else {
                for (std::size_t i = run.first; i < run.last; ++i) {
                    const Emitter& source = emitters[i];
                    const double f = point_to_polygon(x, n, source.polygon.data(), source.count, source.normal);
                    if (!(f > 0.0)) continue;
                    seen.faces[i] = 1;
                    group.light += source.radiance * f;
                    group.area += source.area;
                }
            }
        }
        seen.groups.push_back(group);
    }
    for (const EmitterGroup& group : seen.groups) seen.total += max_channel(group.light);
    return seen;
}

}  // namespace radiosity::detail
