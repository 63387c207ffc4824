/// @file intersection_find.cpp
/// @brief Polygon-polygon intersection segments over a bounding-box tree (see intersection_find.h).
#include "geometry/intersection_find.h"

#include "geometry/box_tree.h"
#include "geometry/polygon_geometry.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace radiosity::detail {
namespace {

struct Plane {
    DVec3 normal;
    double offset = 0.0;     ///< dot(normal, x) on the plane
    double tolerance = 0.0;  ///< plane_tolerance of the polygon
    bool convex = true;
};

void read_corners(const SceneInput& in, std::size_t f, std::vector<DVec3>& p) {
    p.clear();
    for (int32_t k = in.face_offsets[f]; k < in.face_offsets[f + 1]; ++k) {
        const float* q = in.positions + 3 * static_cast<std::size_t>(in.corner_vertices[k]);
        p.emplace_back(q[0], q[1], q[2]);
    }
}

/// The polygon itself when convex, else its ear-clipping triangles: each part meets a line in one interval.
void convex_parts(const std::vector<DVec3>& p, const Plane& plane, std::vector<std::vector<DVec3>>& parts) {
    parts.clear();
    if (plane.convex) {
        parts.push_back(p);
        return;
    }
    for (const auto& t : triangulate(p, plane.normal)) parts.push_back({p[t[0]], p[t[1]], p[t[2]]});
}

/// Whether the corners lie strictly on both sides of the plane, beyond `tolerance`.
bool straddles(const std::vector<DVec3>& p, const Plane& plane, double tolerance) {
    bool above = false, below = false;
    for (const DVec3& q : p) {
        const double d = glm::dot(plane.normal, q) - plane.offset;
        above = above || d > tolerance;
        below = below || d < -tolerance;
    }
    return above && below;
}

/// Whether the corners touch the plane along an edge: two or more within `tolerance` of it, the
/// rest beyond it on one side only (a box's side face standing on a floor).
bool touches(const std::vector<DVec3>& p, const Plane& plane, double tolerance) {
    int on = 0;
    bool above = false, below = false;
    for (const DVec3& q : p) {
        const double d = glm::dot(plane.normal, q) - plane.offset;
        on += std::abs(d) <= tolerance;
        above = above || d > tolerance;
        below = below || d < -tolerance;
    }
    return on >= 2 && above != below;
}

double longest_edge(const std::vector<DVec3>& p) {
    double longest = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k) longest = std::max(longest, glm::length(p[(k + 1) % p.size()] - p[k]));
    return longest;
}

bool emits(const SceneInput& in, std::size_t f) {
    return in.emission[3 * f] > 0.0f || in.emission[3 * f + 1] > 0.0f || in.emission[3 * f + 2] > 0.0f;
}

/// Whether x lies within `tolerance` of the polygon's outline.
bool on_outline(const std::vector<DVec3>& p, const DVec3& x, double tolerance) {
    for (std::size_t k = 0; k < p.size(); ++k) {
        const DVec3 &a = p[k], d = p[(k + 1) % p.size()] - a;
        const double t = std::clamp(glm::dot(x - a, d) / glm::dot(d, d), 0.0, 1.0);
        if (glm::length(x - a - t * d) <= tolerance) return true;
    }
    return false;
}

/// The interval where a convex part crosses the plane, as two points on it; false if shorter than `tolerance`.
bool crossing(const std::vector<DVec3>& part, const Plane& plane, const DVec3& along, double tolerance, DVec3& a,
              DVec3& b) {
    double t_min = std::numeric_limits<double>::infinity(), t_max = -t_min;
    auto take = [&](const DVec3& q) {
        const double t = glm::dot(q, along);
        if (t < t_min) t_min = t, a = q;
        if (t > t_max) t_max = t, b = q;
    };
    for (std::size_t k = 0; k < part.size(); ++k) {
        const DVec3 &p = part[k], &q = part[(k + 1) % part.size()];
        const double dp = glm::dot(plane.normal, p) - plane.offset, dq = glm::dot(plane.normal, q) - plane.offset;
        if (std::abs(dp) <= tolerance)
            take(p - dp * plane.normal);
        else if ((dp > 0.0) != (dq > 0.0) && std::abs(dq) > tolerance)
            take(p + (q - p) * (dp / (dp - dq)));
    }
    return t_max - t_min > tolerance;
}

/// Whether the box lies within `tolerance` of one side of the plane (then no polygon in it crosses the plane).
bool one_side(const Box& box, const Plane& plane, double tolerance) {
    double centre = -plane.offset, radius = 0.0;
    for (int a = 0; a < 3; ++a) {
        centre += plane.normal[a] * 0.5 * (double(box.lo[a]) + double(box.hi[a]));
        radius += std::abs(plane.normal[a]) * 0.5 * (double(box.hi[a]) - double(box.lo[a]));
    }
    return centre - radius >= -tolerance || centre + radius <= tolerance;
}

/// Each polygon's plane; then, per pair, the segments. Holds one thread's scratch.
class Finder {
public:
    /// contact_tolerance < 0: no contact lines.
    Finder(const SceneInput& in, const std::vector<Plane>& planes, double contact_tolerance)
        : in_(in), plane_(planes), contact_tolerance_(contact_tolerance) {}

    /// Appends the segments where polygon a passes through or stands on polygon b, and b on or through a.
    void cut_pair(std::size_t a, std::size_t b, const Box& a_box, const Box& b_box, std::vector<CutSegment>& out) {
        const Plane &pa = plane_[a], &pb = plane_[b];
        // Contacts are measured against the scene: a box set on a floor by hand sits within round-off
        // of it at the scene's scale, not at its own faces'.
        const double tolerance = std::max({pa.tolerance, pb.tolerance, contact_tolerance_});
        // Only a polygon that has corners on both sides of the other's plane can be cut; without
        // contacts, both must have (cheap: most pairs end here).
        const bool contacts = contact_tolerance_ >= 0.0;
        const bool a_cuttable = !one_side(a_box, pb, tolerance), b_cuttable = !one_side(b_box, pa, tolerance);
        if (contacts ? !a_cuttable && !b_cuttable : !a_cuttable || !b_cuttable) return;
        read_corners(in_, a, a_corners_);
        read_corners(in_, b, b_corners_);
        const bool a_straddles = a_cuttable && straddles(a_corners_, pb, tolerance);
        const bool b_straddles = b_cuttable && straddles(b_corners_, pa, tolerance);
        // b is cut where a passes through it or stands on it (a's edge in b's plane, inside b).
        const bool cut_b = b_straddles && (a_straddles || (contacts && touches(a_corners_, pb, tolerance)));
        const bool cut_a = a_straddles && (b_straddles || (contacts && touches(b_corners_, pa, tolerance)));
        if (!cut_a && !cut_b) return;
        const DVec3 common = glm::cross(pa.normal, pb.normal);  // direction of the planes' common line
        if (!(glm::length(common) > 0.0)) return;
        convex_parts(a_corners_, pa, a_parts_);
        convex_parts(b_corners_, pb, b_parts_);
        if (cut_a) cut(a, b, a_corners_, a_parts_, b_parts_, glm::normalize(common), tolerance, !b_straddles, out);
        if (cut_b) cut(b, a, b_corners_, b_parts_, a_parts_, glm::normalize(common), tolerance, !a_straddles, out);
    }

    /// With contacts: appends the segments where polygon f is cut along the outline of emitting
    /// polygon e hung close in front of it, its back side towards f (a light panel under a
    /// ceiling): parallel to within 2.5 degrees, at most kBehind times e's longest edge away. e's
    /// back side lights f up to its outline; an element of f straddling the outline would show
    /// that light to the room on its other side.
    void cut_behind(std::size_t e, std::size_t f, std::vector<CutSegment>& out) {
        const Plane &pe = plane_[e], &pf = plane_[f];
        if (contact_tolerance_ < 0.0 || !(glm::dot(pe.normal, pf.normal) > kParallel)) return;
        read_corners(in_, e, a_corners_);
        read_corners(in_, f, b_corners_);
        const double longest = longest_edge(a_corners_);
        DVec3 centre(0.0);
        for (const DVec3& q : b_corners_) centre += q / double(b_corners_.size());
        const double tolerance = std::max({pe.tolerance, pf.tolerance, contact_tolerance_});
        const double behind = pe.offset - glm::dot(pe.normal, centre);
        if (!(behind > tolerance && behind <= kBehind * longest)) return;
        convex_parts(b_corners_, pf, b_parts_);
        for (std::size_t k = 0; k < a_corners_.size(); ++k) {
            auto onto_f = [&](const DVec3& q) { return q - (glm::dot(pf.normal, q) - pf.offset) * pf.normal; };
            const DVec3 from = onto_f(a_corners_[k]), to = onto_f(a_corners_[(k + 1) % a_corners_.size()]);
            for (const auto& f_part : b_parts_) {
                DVec3 ca = from, cb = to;
                if (clip_segment(f_part, pf.normal, tolerance, ca, cb) &&
                    !on_outline(b_corners_, 0.5 * (ca + cb), tolerance))
                    out.push_back({static_cast<int32_t>(f), static_cast<int32_t>(e), ca, cb});
            }
        }
    }

    static constexpr double kParallel = 0.999;  ///< cos 2.56 degrees
    static constexpr double kBehind = 0.1;

private:
    /// Appends the segments where polygon `by` (its convex parts) passes through or stands on polygon
    /// f. A contact along f's own outline (a concave f sharing an edge with `by`) is no cut: it would
    /// only stop colours blending across a shared edge.
    void cut(std::size_t f, std::size_t by, const std::vector<DVec3>& f_corners,
             const std::vector<std::vector<DVec3>>& f_parts, const std::vector<std::vector<DVec3>>& by_parts,
             const DVec3& along, double tolerance, bool contact, std::vector<CutSegment>& out) const {
        for (const auto& by_part : by_parts) {
            DVec3 a, b;
            if (!crossing(by_part, plane_[f], along, tolerance, a, b)) continue;
            for (const auto& f_part : f_parts) {
                DVec3 ca = a, cb = b;
                if (clip_segment(f_part, plane_[f].normal, tolerance, ca, cb) &&
                    !(contact && on_outline(f_corners, 0.5 * (ca + cb), tolerance)))
                    out.push_back({static_cast<int32_t>(f), static_cast<int32_t>(by), ca, cb});
            }
        }
    }

    const SceneInput& in_;
    const std::vector<Plane>& plane_;
    double contact_tolerance_;
    std::vector<DVec3> a_corners_, b_corners_;
    std::vector<std::vector<DVec3>> a_parts_, b_parts_;
};

Box bounding_box(const SceneInput& in, std::size_t f) {
    Box box{glm::vec3(std::numeric_limits<float>::infinity()), glm::vec3(-std::numeric_limits<float>::infinity())};
    for (int32_t k = in.face_offsets[f]; k < in.face_offsets[f + 1]; ++k) {
        const float* q = in.positions + 3 * static_cast<std::size_t>(in.corner_vertices[k]);
        box.lo = glm::min(box.lo, glm::vec3(q[0], q[1], q[2]));
        box.hi = glm::max(box.hi, glm::vec3(q[0], q[1], q[2]));
    }
    return box;
}

}  // namespace

double plane_tolerance(const std::vector<DVec3>& p) {
    double longest = 0.0, magnitude = 0.0;
    for (std::size_t k = 0; k < p.size(); ++k) {
        longest = std::max(longest, glm::length(p[(k + 1) % p.size()] - p[k]));
        magnitude = std::max({magnitude, std::abs(p[k].x), std::abs(p[k].y), std::abs(p[k].z)});
    }
    return std::max(1e-5 * longest, 16.0 * std::numeric_limits<float>::epsilon() * magnitude);
}

std::vector<CutSegment> find_intersections(const SceneInput& in, const std::vector<char>& usable, bool contacts) {
    std::vector<int32_t> polygon;  // tree index -> polygon
    std::vector<Box> boxes;
    for (std::size_t f = 0; f < in.face_count; ++f)
        if (usable[f]) polygon.push_back(static_cast<int32_t>(f)), boxes.push_back(bounding_box(in, f));
    // With contacts, an emitting polygon's box grows by as far behind it as it cuts (cut_behind).
    std::vector<Box> reach = boxes;
    if (contacts)
        for (std::size_t i = 0; i < reach.size(); ++i)
            if (emits(in, std::size_t(polygon[i]))) {
                const glm::vec3 size = reach[i].hi - reach[i].lo;
                const float grow = 2.0f * float(Finder::kBehind) * std::max({size.x, size.y, size.z});
                reach[i].lo -= glm::vec3(grow);
                reach[i].hi += glm::vec3(grow);
            }
    const BoxTree tree(reach);
    Box scene{glm::vec3(std::numeric_limits<float>::infinity()), glm::vec3(-std::numeric_limits<float>::infinity())};
    for (const Box& box : boxes) scene.lo = glm::min(scene.lo, box.lo), scene.hi = glm::max(scene.hi, box.hi);
    // As weld_tolerance: 1e-5 of the scene's diagonal.
    const double contact_tolerance = !contacts       ? -1.0
                                     : boxes.empty() ? 0.0
                                                     : 1e-5 * glm::length(glm::dvec3(scene.hi) - glm::dvec3(scene.lo));
    std::vector<Plane> planes(in.face_count);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, in.face_count), [&](const auto& range) {
        std::vector<DVec3> p;
        for (std::size_t f = range.begin(); f != range.end(); ++f) {
            if (!usable[f]) continue;
            read_corners(in, f, p);
            Plane& plane = planes[f];
            plane.normal = glm::normalize(newell(p));
            plane.offset = glm::dot(plane.normal, p[0]);
            plane.tolerance = plane_tolerance(p);
            plane.convex = p.size() == 3 || is_convex(p, plane.normal);
        }
    });
    tbb::enumerable_thread_specific<Finder> finders(in, planes, contact_tolerance);
    tbb::enumerable_thread_specific<std::vector<CutSegment>> found;
    tree.visit_overlapping_pairs([&](int32_t i, int32_t j) {
        const std::size_t a = std::size_t(polygon[i]), b = std::size_t(polygon[j]);
        Finder& finder = finders.local();
        finder.cut_pair(a, b, boxes[i], boxes[j], found.local());
        if (contacts && emits(in, a)) finder.cut_behind(a, b, found.local());
        if (contacts && emits(in, b)) finder.cut_behind(b, a, found.local());
    });
    std::vector<CutSegment> segments;
    for (const auto& part : found) segments.insert(segments.end(), part.begin(), part.end());
    // Threads finish in any order; one pair's segments come from one call, in its order, which the
    // stable sort keeps: the result does not depend on the threads.
    std::stable_sort(segments.begin(), segments.end(), [](const CutSegment& x, const CutSegment& y) {
        return x.polygon != y.polygon ? x.polygon < y.polygon : x.by < y.by;
    });
    return segments;
}

}  // namespace radiosity::detail
