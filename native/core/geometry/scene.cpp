/// @file scene.cpp
/// @brief build_elements: validates the input arrays, cuts polygons along intersections, splits n-gons and
/// subdivides polygons into elements.
///
/// Corner indices out of range are a defect of one polygon, not of the arrays as a whole: such a
/// polygon is skipped and reported as Defect::BadIndex, like a degenerate one.

#include "geometry/scene.h"

#include "common/report_progress.h"
#include "geometry/intersection_cut.h"
#include "geometry/intersection_find.h"
#include "geometry/polygon_geometry.h"
#include "geometry/surface_textures.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

namespace radiosity {
namespace {

using detail::DVec3;

bool emits_front_only(const SceneInput& in, std::size_t f) { return in.front_only != nullptr && in.front_only[f] != 0; }
bool has_open_back(const SceneInput& in, std::size_t f) { return in.open_back != nullptr && in.open_back[f] != 0; }

[[noreturn]] void fail(std::size_t polygon, const std::string& what) {
    throw InputError("polygon " + std::to_string(polygon) + ": " + what);
}

void validate_arrays(const SceneInput& in) {
    if (in.face_count == 0) return;
    if (!in.face_offsets || !in.corner_vertices || !in.reflectance || !in.emission ||
        (!in.positions && in.vertex_count))
        throw InputError("scene arrays: a required array is null");
    if (in.face_offsets[0] != 0) fail(0, "face offsets must start at 0");
    for (std::size_t f = 0; f < in.face_count; ++f)
        if (in.face_offsets[f + 1] < in.face_offsets[f]) fail(f, "face offsets decrease");
    validate_materials(in);
}

/// Number of segments an edge of this length is cut into so that each is at most max_edge.
/// A double, so that absurd ratios (1e6 m at 1e-6 m) are counted, not overflowed, before the cap.
double segments(double length, float max_edge) {
    if (max_edge <= 0.0f) return 1.0;
    // The small slack keeps an edge of exactly k * max_edge at k segments despite rounding.
    return std::max(1.0, std::ceil(length / max_edge * (1.0 - 1e-6)));
}

/// A face's light is its area times its radiance: a face of negligible area carries negligible light,
/// so the aspect cut makes no piece shorter than 1/kSliverDivisions of the element size, nor of less
/// area than the square of that. The elements from any face are then bounded by its size and area,
/// never by its aspect.
constexpr double kSliverDivisions = 32.0;

/// The aspect cut of one polygon (ElementLimits::max_aspect).
struct AspectCut {
    double max_aspect = 0.0;  ///< 0: off
    double size = 0.0;        ///< the element size the floors are fractions of
    bool area_floor = false;  ///< size is the bake's element size (not the polygon's own length)

    /// The shortest piece the cut makes along a strip `width` wide.
    double shortest(double width) const {
        const double floor = size / kSliverDivisions;
        double length = std::max(max_aspect * width, floor);
        if (area_floor) length = std::max(length, std::min(size, floor * floor / width));
        return length;
    }
};

/// The aspect cut for polygon p: its floors are fractions of max_edge, else of
/// ElementLimits::element_size, else (one element per polygon, no size given) of p's longest edge.
AspectCut aspect_cut(const ElementLimits& limits, float max_edge, const std::vector<DVec3>& p) {
    AspectCut cut;
    if (!(limits.max_aspect >= 1.0f)) return cut;
    cut.max_aspect = limits.max_aspect;
    cut.size = max_edge > 0.0f ? max_edge : limits.element_size;
    cut.area_floor = cut.size > 0.0;
    if (!cut.area_floor)
        for (std::size_t k = 0; k < p.size(); ++k)
            cut.size = std::max(cut.size, glm::length(p[(k + 1) % p.size()] - p[k]));
    return cut;
}

/// Counts (long, short) of a quad's two directions after the aspect cut: the long direction is
/// cut until its elements are at most max_aspect times as long as the short direction's, within
/// the cut's floors.
void limit_aspect(double length_u, double length_v, const AspectCut& cut, double& nu, double& nv) {
    if (!(cut.max_aspect >= 1.0) || !(length_u > 0.0) || !(length_v > 0.0)) return;
    const double du = length_u / nu, dv = length_v / nv;
    if (du > cut.max_aspect * dv) nu = std::max(nu, std::ceil(length_u / cut.shortest(dv) * (1.0 - 1e-6)));
    if (dv > cut.max_aspect * du) nv = std::max(nv, std::ceil(length_v / cut.shortest(du) * (1.0 - 1e-6)));
}

/// Builds the elements of one polygon. Vertices on a polygon edge or diagonal are shared by
/// the elements on both sides of it; they are placed by a lerp that gives bit-identical points
/// from either end, so that coincident edges of neighbouring polygons match exactly too.
class PolygonBuilder {
public:
    PolygonBuilder(Elements& out, const std::vector<DVec3>& p, int32_t polygon, const Rgb& rho, const Rgb& emitted)
        : out_(out), p_(p), polygon_(polygon), rho_(rho), emitted_(emitted) {
        for (const DVec3& q : p) corner_.push_back(add_vertex(q));
    }

    int32_t corner(int i) const { return corner_[i]; }

    /// Regular subdivision into n^2 triangles (a, b, c local corner indices).
    void triangle(int a, int b, int c, int n) {
        // grid(i, j): the point a + i/n (b - a) + j/n (c - a), i + j <= n.
        std::vector<int32_t> grid((n + 1) * (n + 1), -1);
        auto at = [&](int i, int j) -> int32_t& { return grid[i * (n + 1) + j]; };
        const auto ab = edge(a, b, n), ac = edge(a, c, n), bc = edge(b, c, n);
        for (int i = 0; i <= n; ++i)
            for (int j = 0; i + j <= n; ++j) {
                if (j == 0)
                    at(i, j) = ab[i];
                else if (i == 0)
                    at(i, j) = ac[j];
                else if (i + j == n)
                    at(i, j) = bc[j];
                else
                    at(i, j) =
                        add_vertex(p_[a] + (p_[b] - p_[a]) * (double(i) / n) + (p_[c] - p_[a]) * (double(j) / n));
            }
        for (int i = 0; i < n; ++i)
            for (int j = 0; i + j < n; ++j) {
                add_element({at(i, j), at(i + 1, j), at(i, j + 1), -1});
                if (i + j < n - 1) add_element({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), -1});
            }
    }

    /// A strip of nu rows from corner `apex` to the edge (b, c), rows parallel to b-c, each cut into
    /// nv: a fan of triangles at the apex, trapezoids beyond (the elements of a sliver triangle).
    void strip(int apex, int b, int c, int nu, int nv) {
        const auto ab = edge(apex, b, nu), ac = edge(apex, c, nu), bc = edge(b, c, nv);
        std::vector<int32_t> row(nv + 1), previous;
        for (int i = 1; i <= nu; ++i) {
            for (int j = 0; j <= nv; ++j) {
                if (j == 0)
                    row[j] = ab[i];
                else if (j == nv)
                    row[j] = ac[i];
                else if (i == nu)
                    row[j] = bc[j];
                else {
                    const double s = double(j) / nv;
                    row[j] = add_vertex((1 - s) * DVec3(out_.vertices[ab[i]]) + s * DVec3(out_.vertices[ac[i]]));
                }
            }
            for (int j = 0; j < nv; ++j) {
                if (i == 1)
                    add_element({corner_[apex], row[j], row[j + 1], -1});
                else
                    add_element({previous[j], row[j], row[j + 1], previous[j + 1]});
            }
            previous = row;
        }
    }

    /// Bilinear grid of nu x nv quads over the convex quad (a, b, c, d).
    void quad(int a, int b, int c, int d, int nu, int nv) {
        std::vector<int32_t> grid((nu + 1) * (nv + 1));
        auto at = [&](int i, int j) -> int32_t& { return grid[j * (nu + 1) + i]; };
        const auto ab = edge(a, b, nu), dc = edge(d, c, nu), ad = edge(a, d, nv), bc = edge(b, c, nv);
        for (int j = 0; j <= nv; ++j)
            for (int i = 0; i <= nu; ++i) {
                if (j == 0)
                    at(i, j) = ab[i];
                else if (j == nv)
                    at(i, j) = dc[i];
                else if (i == 0)
                    at(i, j) = ad[j];
                else if (i == nu)
                    at(i, j) = bc[j];
                else {
                    const double s = double(i) / nu, t = double(j) / nv;
                    at(i, j) = add_vertex((1 - s) * (1 - t) * p_[a] + s * (1 - t) * p_[b] + s * t * p_[c] +
                                          (1 - s) * t * p_[d]);
                }
            }
        for (int j = 0; j < nv; ++j)
            for (int i = 0; i < nu; ++i) add_element({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
    }

private:
    int32_t add_vertex(const DVec3& q) {
        out_.vertices.emplace_back(q);
        return static_cast<int32_t>(out_.vertices.size()) - 1;
    }

    /// The n + 1 vertices from corner i to corner j, created on first use (a diagonal between two
    /// convex pieces cut by different counts has a set for each).
    std::vector<int32_t> edge(int i, int j, int n) {
        const bool flip = i > j;
        const auto key = std::make_tuple(std::min(i, j), std::max(i, j), n);
        auto found = edges_.find(key);
        if (found == edges_.end()) {
            const Vec3 from(p_[std::get<0>(key)]), to(p_[std::get<1>(key)]);
            std::vector<int32_t> v(n + 1);
            v[0] = corner_[std::get<0>(key)];
            v[n] = corner_[std::get<1>(key)];
            for (int k = 1; k < n; ++k) v[k] = add_vertex(DVec3(symmetric_lerp(from, to, k, n)));
            found = edges_.emplace(key, std::move(v)).first;
        }
        std::vector<int32_t> v = found->second;
        if (flip) std::reverse(v.begin(), v.end());
        return v;
    }

    /// Point k of n along from->to, computed from the nearer end so that (to, from, n - k) gives the same bits.
    static Vec3 symmetric_lerp(const Vec3& from, const Vec3& to, int k, int n) {
        if (2 * k == n) return (from + to) * 0.5f;
        if (2 * k < n) return from + (to - from) * (float(k) / float(n));
        return to + (from - to) * (float(n - k) / float(n));
    }

    void add_element(const std::array<int32_t, 4>& c) {
        const DVec3 a(out_.vertices[c[0]]), b(out_.vertices[c[1]]), d(out_.vertices[c[2]]);
        DVec3 centre, twice_area;
        if (c[3] < 0) {
            twice_area = glm::cross(b - a, d - a);
            centre = (a + b + d) / 3.0;
        } else {
            const DVec3 e(out_.vertices[c[3]]);
            const DVec3 n1 = glm::cross(b - a, d - a), n2 = glm::cross(d - a, e - a);
            twice_area = n1 + n2;
            const double w1 = glm::length(n1), w2 = glm::length(n2);
            centre = (w1 * (a + b + d) / 3.0 + w2 * (a + d + e) / 3.0) / (w1 + w2);
        }
        const double length = glm::length(twice_area);
        // Collinear corners of an n-gon can leave zero-area ears: they carry no light.
        if (!(length > 0.0)) return;
        out_.corners.push_back(c);
        out_.centre.emplace_back(centre);
        out_.normal.emplace_back(twice_area / length);
        out_.area.push_back(static_cast<float>(0.5 * length));
        out_.polygon.push_back(polygon_);
        out_.reflectance.push_back(rho_);
        out_.emission.push_back(emitted_);
        out_.cut_edges.push_back(0);
    }

    Elements& out_;
    const std::vector<DVec3>& p_;
    int32_t polygon_;
    Rgb rho_, emitted_;
    std::vector<int32_t> corner_;
    std::map<std::tuple<int, int, int>, std::vector<int32_t>> edges_;
};

/// Heights below this many times a polygon's largest coordinate are float round-off: two units in
/// the last place of a float (2^-23 each, relative). Whether corners are collinear cannot be decided
/// below the rounding of their coordinates (the error bound of an orientation test grows with the
/// coordinates' magnitude: Shewchuk 1997, "Adaptive Precision Floating-Point Arithmetic and Fast
/// Robust Geometric Predicates", Discrete & Computational Geometry 18).
constexpr double kRoundOffHeight = 2.0 / double(1 << 23);

/// Reads polygon f's corners into p and its unit normal, or returns why it cannot be used.
std::optional<Defect> read_polygon(const SceneInput& in, std::size_t f, std::vector<DVec3>& p, DVec3& normal) {
    const int32_t first = in.face_offsets[f], count = in.face_offsets[f + 1] - first;
    if (count < 3) return Defect::TooFewCorners;
    p.clear();
    bool finite = true;
    for (int32_t k = 0; k < count; ++k) {
        const int32_t v = in.corner_vertices[first + k];
        if (v < 0 || static_cast<std::size_t>(v) >= in.vertex_count) return Defect::BadIndex;
        const float* q = in.positions + 3 * static_cast<std::size_t>(v);
        finite = finite && std::isfinite(q[0]) && std::isfinite(q[1]) && std::isfinite(q[2]);
        p.emplace_back(q[0], q[1], q[2]);
    }
    if (!finite) return Defect::NonFinite;
    const DVec3 twice_area = detail::newell(p);
    double longest = 0.0, farthest = 0.0;
    for (int32_t k = 0; k < count; ++k) {
        longest = std::max(longest, glm::length(p[(k + 1) % count] - p[k]));
        farthest = std::max({farthest, std::abs(p[k].x), std::abs(p[k].y), std::abs(p[k].z)});
    }
    // Zero area at float precision (the input is float): relative to the polygon's size, or a height
    // over its longest edge within round-off of its corners' coordinates (collinear corners rounded
    // apart; its plane, and so its normal, would be round-off).
    const double doubled = glm::length(twice_area);
    if (!(doubled > 1e-7 * longest * longest) || !(doubled > kRoundOffHeight * farthest * longest))
        return Defect::ZeroArea;
    normal = glm::normalize(twice_area);
    return std::nullopt;
}

/// A convex piece of a concave polygon: its corners (indices of the polygon's), and how it is cut:
/// a quad into nu x nv, anything else as triangles of its corners, each into nu^2.
struct Piece {
    std::vector<int> corners;
    std::vector<std::array<int, 3>> triangles;
    double nu, nv;
};

/// Subdivides one convex or concave polygon (or cut piece) of input polygon f into elements;
/// returns the element vertices of its corners.
std::vector<int32_t> subdivide(Elements& out, const std::vector<DVec3>& p, const DVec3& normal, std::size_t f,
                               const Rgb& rho, const Rgb& emitted, bool two_sided, float max_edge,
                               const ElementLimits& limits, std::size_t& back_sides) {
    const int count = static_cast<int>(p.size());
    const detail::SliverSplit sliver =
        count == 3 ? detail::split_sliver(p[0], p[1], p[2], limits.max_aspect) : detail::SliverSplit{};
    std::vector<DVec3> points = p;  // a cap sliver's altitude foot joins as point 3
    if (sliver.at_foot) points.push_back(sliver.foot);
    auto length = [&](int i, int j) { return glm::length(points[j] - points[i]); };
    // Counts first, checked against the cap in double, before any element is made. A two-sided
    // polygon has its elements each get a back side (add_back_sides): they count twice.
    auto check_cap = [&](double elements) {
        if (two_sided) elements *= 2.0;
        if (double(out.size() + back_sides) + elements > double(limits.max_elements)) {
            char what[200];
            std::snprintf(what, sizeof what,
                          "element_size %g m would make %.3g elements from this polygon%s, beyond the cap of %zu "
                          "for the scene; raise element_size",
                          double(max_edge), elements,
                          !two_sided                   ? ""
                          : max_channel(emitted) > 0.0 ? " (both sides: it emits)"
                                                       : " (both sides: its back looks into the scene)",
                          limits.max_elements);
            throw BudgetError("polygon " + std::to_string(f) + ": " + what);
        }
    };
    const AspectCut aspect = aspect_cut(limits, max_edge, p);
    const std::size_t first_element = out.size();
    PolygonBuilder build(out, points, static_cast<int32_t>(f), rho, emitted);
    // A strip from `apex` to the edge (b, c): cut along until no row is longer than max_aspect
    // times the far edge's pieces, within the cut's floors (as limit_aspect cuts quads); nv across,
    // as that edge asks.
    auto strip_rows = [&](int apex, int b, int c, double nv) {
        double nu = std::max(segments(length(apex, b), max_edge), segments(length(apex, c), max_edge));
        limit_aspect(std::max(length(apex, b), length(apex, c)), length(b, c), aspect, nu, nv);
        return nu;
    };
    if (sliver.at_foot) {
        // Two right triangles (a, foot, r) and (foot, b, r) share the altitude foot-r, cut nv times.
        const int a = sliver.longest, b = (a + 1) % 3, r = (a + 2) % 3, foot = 3;
        const double nv = segments(length(r, foot), max_edge);
        const double nu_a = strip_rows(a, foot, r, nv), nu_b = strip_rows(b, r, foot, nv);
        check_cap((nu_a + nu_b) * nv);
        build.strip(a, foot, r, static_cast<int>(nu_a), static_cast<int>(nv));
        build.strip(b, r, foot, static_cast<int>(nu_b), static_cast<int>(nv));
    } else if (sliver.sliver) {
        const int apex = sliver.apex, b = (apex + 1) % 3, c = (apex + 2) % 3;
        const double nv = segments(length(b, c), max_edge), nu = strip_rows(apex, b, c, nv);
        check_cap(nu * nv);
        build.strip(apex, b, c, static_cast<int>(nu), static_cast<int>(nv));
    } else if (count == 3) {
        // Regular subdivision needs one count for all three edges, so a short edge may be cut
        // finer than its own length asks for (a T-vertex against a neighbour on that edge).
        const double n = std::max(
            {segments(length(0, 1), max_edge), segments(length(1, 2), max_edge), segments(length(2, 0), max_edge)});
        check_cap(n * n);
        build.triangle(0, 1, 2, static_cast<int>(n));
    } else if (count == 4 && detail::is_convex(p, normal)) {
        // Opposite edges share a count; they agree with their neighbours when they are equally long.
        double nu = std::max(segments(length(0, 1), max_edge), segments(length(3, 2), max_edge));
        double nv = std::max(segments(length(0, 3), max_edge), segments(length(1, 2), max_edge));
        limit_aspect(std::max(length(0, 1), length(3, 2)), std::max(length(0, 3), length(1, 2)), aspect, nu, nv);
        check_cap(nu * nv);
        build.quad(0, 1, 2, 3, static_cast<int>(nu), static_cast<int>(nv));
    } else {
        // Concave quads and n-gons: convex pieces, each cut by its own counts (a short piece is not
        // cut as finely as the longest edge of the whole asks). Pieces meet along diagonals; where
        // their counts differ, each keeps its own vertices there (T-vertices inside one plane).
        std::vector<Piece> pieces;
        double total = 0.0;
        for (const std::vector<int>& corners : detail::convex_pieces(p, normal)) {
            Piece piece{corners, {}, 1.0, 1.0};
            const int m = int(corners.size());
            auto edge_length = [&](int i, int j) { return length(corners[i % m], corners[j % m]); };
            if (m == 4) {
                piece.nu = std::max(segments(edge_length(0, 1), max_edge), segments(edge_length(3, 2), max_edge));
                piece.nv = std::max(segments(edge_length(0, 3), max_edge), segments(edge_length(1, 2), max_edge));
                limit_aspect(std::max(edge_length(0, 1), edge_length(3, 2)),
                             std::max(edge_length(0, 3), edge_length(1, 2)), aspect, piece.nu, piece.nv);
                total += piece.nu * piece.nv;
            } else {
                if (m == 3) {
                    piece.triangles.push_back({0, 1, 2});
                } else {  // a convex n-gon: its own ear clipping
                    std::vector<DVec3> q;
                    for (const int c : corners) q.push_back(p[std::size_t(c)]);
                    piece.triangles = detail::triangulate(q, normal);
                }
                for (const auto& t : piece.triangles)
                    piece.nu = std::max({piece.nu, segments(edge_length(t[0], t[1]), max_edge),
                                         segments(edge_length(t[1], t[2]), max_edge),
                                         segments(edge_length(t[2], t[0]), max_edge)});
                total += double(piece.triangles.size()) * piece.nu * piece.nu;
            }
            pieces.push_back(std::move(piece));
        }
        check_cap(total);
        for (const Piece& piece : pieces) {
            const std::vector<int>& c = piece.corners;
            if (c.size() == 4) {
                build.quad(c[0], c[1], c[2], c[3], int(piece.nu), int(piece.nv));
            } else {
                for (const auto& t : piece.triangles) build.triangle(c[t[0]], c[t[1]], c[t[2]], int(piece.nu));
            }
        }
    }
    if (two_sided) back_sides += out.size() - first_element;
    std::vector<int32_t> corners(p.size());
    for (int k = 0; k < count; ++k) corners[k] = build.corner(k);
    return corners;
}

/// Emitting polygons emit from both sides, as in Cycles (except those marked front only, Cycles'
/// area lamps: SceneInput::front_only), and polygons with an open back (SceneInput::open_back)
/// reflect from both sides: each of their elements gets a twin on
/// the same vertices, corners reversed, facing the other way (Elements::side). The twin shares the
/// front's vertices, so that everything that renders or traces the elements sees the two sides
/// at exactly one place; its cut-edge bits follow its reversed corners. `back_sides` is their
/// count, which subdivide() checked against the element cap.
void add_back_sides(Elements& out, const SceneInput& in, std::size_t back_sides) {
    if (back_sides == 0) return;
    const std::size_t fronts = out.size();
    out.side.assign(fronts, Elements::kOneSided);
    for (std::size_t e = 0; e < fronts; ++e) {
        const std::size_t f = std::size_t(out.polygon[e]);
        if (emits_front_only(in, f) || !(max_channel(out.emission[e]) > 0.0 || has_open_back(in, f))) continue;
        out.side[e] = Elements::kFront;
        const std::array<int32_t, 4> c = out.corners[e];
        const bool triangle = c[3] < 0;
        // Quad (0 1 2 3) -> (0 3 2 1): new edge k is old edge 3 - k. Triangle (0 1 2) -> (0 2 1):
        // new edge k is old edge 2 - k.
        const int count = triangle ? 3 : 4;
        out.corners.push_back(triangle ? std::array<int32_t, 4>{c[0], c[2], c[1], -1}
                                       : std::array<int32_t, 4>{c[0], c[3], c[2], c[1]});
        uint8_t bits = 0;
        for (int k = 0; k < count; ++k)
            if ((out.cut_edges[e] >> (count - 1 - k)) & 1u) bits |= uint8_t(1u << k);
        out.cut_edges.push_back(bits);
        out.centre.push_back(out.centre[e]);
        out.normal.push_back(-out.normal[e]);
        out.area.push_back(out.area[e]);
        out.polygon.push_back(out.polygon[e]);
        out.reflectance.push_back(out.reflectance[e]);
        out.emission.push_back(out.emission[e]);
        out.side.push_back(Elements::kBack);
    }
}

}  // namespace

void validate_materials(const SceneInput& in) {
    for (std::size_t f = 0; f < in.face_count; ++f)
        for (int c = 0; c < 3; ++c) {
            const float rho = in.reflectance[3 * f + c];
            if (!(rho >= 0.0f && rho < 1.0f)) fail(f, "reflectance " + std::to_string(rho) + " outside [0, 1)");
            const float emitted = in.emission[3 * f + c];
            if (!(emitted >= 0.0f && std::isfinite(emitted)))
                fail(f, "emission " + std::to_string(emitted) + " negative or not finite");
        }
    if (in.textures) validate_textures(*in.textures, in.face_count, std::size_t(in.face_offsets[in.face_count]));
}

BuildResult build_elements(const SceneInput& in, float max_edge, const ElementLimits& limits,
                           const ProgressFn& progress) {
    if (!(max_edge >= 0.0f) || !std::isfinite(max_edge)) throw InputError("max_edge must be finite and >= 0");
    validate_arrays(in);
    detail::report_progress(progress, "elements", 0, in.face_count);  // before the intersections are found
    BuildResult result;
    Elements& out = result.elements;
    const std::size_t corner_count = in.face_count ? static_cast<std::size_t>(in.face_offsets[in.face_count]) : 0;
    out.corner_vertex.assign(corner_count, -1);

    std::vector<DVec3> p;
    DVec3 normal;
    std::vector<char> usable(in.face_count, 0);
    for (std::size_t f = 0; f < in.face_count; ++f) {
        const std::optional<Defect> defect = read_polygon(in, f, p, normal);
        if (defect)
            result.skipped.push_back({static_cast<int32_t>(f), *defect});
        else
            usable[f] = 1;
    }
    const std::vector<detail::CutSegment> cuts = limits.cut_intersections
                                                     ? detail::find_intersections(in, usable, limits.cut_contacts)
                                                     : std::vector<detail::CutSegment>{};

    auto cut = cuts.begin();
    std::size_t back_sides = 0;  // elements of two-sided polygons, each to get a back side
    const std::size_t report_every = std::max<std::size_t>(1, in.face_count / 100);
    for (std::size_t f = 0; f < in.face_count; ++f) {
        if (f > 0 && f % report_every == 0) detail::report_progress(progress, "elements", f, in.face_count);
        if (!usable[f]) continue;
        read_polygon(in, f, p, normal);
        const int32_t first = in.face_offsets[f];
        const Rgb rho(in.reflectance[3 * f], in.reflectance[3 * f + 1], in.reflectance[3 * f + 2]);
        const Rgb emitted(in.emission[3 * f], in.emission[3 * f + 1], in.emission[3 * f + 2]);
        const bool two_sided = !emits_front_only(in, f) && (max_channel(emitted) > 0.0 || has_open_back(in, f));
        const float edge = polygon_max_edge(limits.polygon_edge, f, max_edge);
        const auto cut_end =
            std::find_if(cut, cuts.end(), [&](const detail::CutSegment& s) { return s.polygon != int32_t(f); });
        if (cut == cut_end) {
            const std::vector<int32_t> corners =
                subdivide(out, p, normal, f, rho, emitted, two_sided, edge, limits, back_sides);
            for (std::size_t k = 0; k < corners.size(); ++k) out.corner_vertex[first + k] = corners[k];
            continue;
        }
        const detail::CutSegment *segments_begin = &*cut, *segments_end = segments_begin + (cut_end - cut);
        const double tolerance = detail::plane_tolerance(p);
        const std::size_t first_element = out.size();
        for (const detail::Piece& piece : detail::cut_polygon(p, normal, segments_begin, segments_end, tolerance)) {
            const std::vector<int32_t> corners =
                subdivide(out, piece.points, normal, f, rho, emitted, two_sided, edge, limits, back_sides);
            for (std::size_t k = 0; k < corners.size(); ++k)
                if (piece.corner[k] >= 0) out.corner_vertex[first + piece.corner[k]] = corners[k];
        }
        detail::mark_cut_edges(out, first_element, segments_begin, segments_end, tolerance);
        cut = cut_end;
    }
    add_back_sides(out, in, back_sides);
    if (in.front_only != nullptr) {
        out.lamp.assign(out.size(), 0);
        for (std::size_t e = 0; e < out.size(); ++e) out.lamp[e] = emits_front_only(in, std::size_t(out.polygon[e]));
    }
    detail::report_progress(progress, "elements", in.face_count, in.face_count);
    if (in.textures) detail::texture_elements(in, out, progress);
    result.polygon_edge = limits.polygon_edge;
    return result;
}

float polygon_max_edge(const std::vector<float>& polygon_edge, std::size_t polygon, float max_edge) {
    if (polygon >= polygon_edge.size() || !(polygon_edge[polygon] > 0.0f)) return max_edge;
    return max_edge > 0.0f ? std::min(max_edge, polygon_edge[polygon]) : polygon_edge[polygon];
}

float scene_diagonal(const std::vector<Vec3>& points) {
    if (points.empty()) return 1.0f;
    Vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (const Vec3& v : points) {
        low = glm::min(low, v);
        high = glm::max(high, v);
    }
    return std::max(glm::length(high - low), 1e-6f);
}

}  // namespace radiosity
