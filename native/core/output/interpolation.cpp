/// @file interpolation.cpp
/// @brief Element radiances to corner colours (seed 23.5), per element corner ("slot").
///
/// A slot (element e, corner k) sits on a welded vertex w. Its compatible set S is the elements at
/// w whose normals differ from e's by at most the hard-edge angle and whose material is e's; where
/// an intersection line (Elements::cut_edges) passes w, only those of them that reach e around w
/// through edges not on the line (the dark side of a wall through a floor is not blended in). The
/// slot is on a border when some edge at w is used by only one element of S (open boundary, hard
/// edge, material change); otherwise it is interior. Then:
///  1. interior slot: the mean radiance of S (seed: B(e) = (B1 + B2 + B3 + B4) / 4);
///  2. border slot: the least-squares plane through the samples S knows - its elements' radiances
///     at their centres and its elements' interior corners (step 1) - evaluated at w.
/// Step 2 is the classic border extrapolation B(a) = B1 + (B1 - B(e)) made general: on a 2x2 example the samples for a
/// are B1 and B(e), collinear with a, giving B(a) = B1 + (B1 - B(e)); for b they are B1, B2, B(e),
/// giving B1 + B2 - B(e) = (B(a) + B(c)) / 2. It is exact for every linear field on any grid of
/// quads or triangles, which "mean of per-element extrapolations B_f + (B_f - mean interior)" is
/// not (on a 3x3 grid that rule puts a border vertex next to a grid corner a quarter of an element
/// off). Where S's samples leave the value open (one sample, or a line missing the vertex) the
/// elements around S's corners join the samples; an element alone keeps its own radiance.
/// Values are clamped at zero per channel. Elements of one smooth surface get equal sets, so their
/// shared corners get one value and the colours join without seams.
///  3. a vertex inside a compatible neighbour's edge (T-vertex) takes that edge's linear colour.
/// An emitter's back side (Elements::side) takes no part: its corners stay zero, and the mesh
/// shows its front.
#include "output/interpolation.h"

#include "geometry/weld.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <utility>

namespace radiosity {
namespace {

/// Slots, their welded vertices and compatible sets; slot index = 4 e + k.
class Slots {
public:
    Slots(const Elements& elements, const int32_t* material, float hard_edge_angle)
        : elements_(elements),
          material_(material),
          cos_hard_(std::cos(hard_edge_angle) - 1e-6f),
          tolerance_(detail::weld_tolerance(elements.vertices)) {
        std::size_t welds = 0;
        weld_ = detail::weld_points(elements.vertices, tolerance_, welds);
        // Slots incident to each weld, as compressed rows.
        std::vector<int32_t>& start = incident_start_;
        start.assign(welds + 1, 0);
        for (std::size_t e = 0; e < size(); ++e)
            for (int k = 0; k < written_corners(e); ++k) ++start[weld(e, k) + 1];
        for (std::size_t w = 0; w < welds; ++w) start[w + 1] += start[w];
        std::vector<int32_t>& incident = incident_;
        incident.resize(start[welds]);
        std::vector<int32_t> fill(start.begin(), start.end() - 1);
        for (std::size_t e = 0; e < size(); ++e)
            for (int k = 0; k < written_corners(e); ++k) incident[fill[weld(e, k)]++] = slot(e, k);
        mark_cut_welds(welds);
        // Compatible set and border flag of every slot.
        set_start_.assign(4 * size() + 1, 0);
        border_.assign(4 * size(), false);
        for (std::size_t e = 0; e < size(); ++e) {
            for (int k = 0; k < 4; ++k) {
                const int32_t s = slot(e, k);
                if (k < written_corners(e)) {
                    const int32_t w = weld(e, k);
                    const std::size_t set_begin = set_.size();
                    for (int32_t t = start[w]; t < start[w + 1]; ++t)
                        if (compatible(e, element_of(incident[t]))) set_.push_back(incident[t]);
                    if (cut_weld_[w]) keep_reachable(s, set_begin);
                }
                set_start_[s + 1] = static_cast<int32_t>(set_.size());
                if (k < written_corners(e)) border_[s] = has_single_edge(s);
            }
        }
    }

    std::size_t size() const { return elements_.size(); }
    int corner_count(std::size_t e) const { return elements_.is_triangle(e) ? 3 : 4; }
    /// Corners whose colour is written: none for an emitter's back side (Elements::side), which
    /// is in no slot's set and keeps zero colours; the mesh shows the front.
    int written_corners(std::size_t e) const { return elements_.is_back(e) ? 0 : corner_count(e); }
    static int32_t slot(std::size_t e, int k) { return static_cast<int32_t>(4 * e) + k; }
    static std::size_t element_of(int32_t s) { return static_cast<std::size_t>(s / 4); }
    static int corner_of(int32_t s) { return s % 4; }
    int32_t weld(std::size_t e, int k) const { return weld_[elements_.corners[e][k]]; }
    float tolerance() const { return tolerance_; }
    /// Every slot on weld w.
    const int32_t* incident_begin(int32_t w) const { return incident_.data() + incident_start_[w]; }
    const int32_t* incident_end(int32_t w) const { return incident_.data() + incident_start_[w + 1]; }
    /// Whether the edge from corner k to k + 1 lies on an intersection line.
    bool cut_edge(std::size_t e, int k) const {
        return !elements_.cut_edges.empty() && ((elements_.cut_edges[e] >> k) & 1u);
    }
    bool border(int32_t s) const { return border_[s]; }

    /// The slots of S: the compatible elements at this slot's vertex, with their corner there.
    const int32_t* set_begin(int32_t s) const { return set_.data() + set_start_[s]; }
    const int32_t* set_end(int32_t s) const { return set_.data() + set_start_[s + 1]; }

    /// Whether an edge at this slot's vertex is used by only one element of S.
    bool has_single_edge(int32_t s) const {
        std::vector<int32_t> ends;  // far-end welds of every edge at the vertex, over S
        for (const int32_t* t = set_begin(s); t != set_end(s); ++t) {
            const std::size_t f = element_of(*t);
            const int m = corner_count(f), kf = corner_of(*t);
            ends.push_back(weld(f, (kf + 1) % m));
            ends.push_back(weld(f, (kf + m - 1) % m));
        }
        for (const int32_t a : ends)
            if (std::count(ends.begin(), ends.end(), a) == 1) return true;
        return false;
    }

    bool compatible(std::size_t e, std::size_t f) const {
        if (glm::dot(elements_.normal[e], elements_.normal[f]) < cos_hard_) return false;
        return material_ == nullptr || material_[elements_.polygon[e]] == material_[elements_.polygon[f]];
    }

private:
    /// An element's two edges at a slot's vertex: far-end weld and whether it lies on a cut.
    struct EdgeAt {
        int32_t far;
        bool cut;
    };
    std::array<EdgeAt, 2> edges_at(int32_t s) const {
        const std::size_t f = element_of(s);
        const int m = corner_count(f), k = corner_of(s), before = (k + m - 1) % m;
        const unsigned bits = elements_.cut_edges.empty() ? 0u : elements_.cut_edges[f];
        return {{{weld(f, (k + 1) % m), ((bits >> k) & 1u) != 0}, {weld(f, before), ((bits >> before) & 1u) != 0}}};
    }

    void mark_cut_welds(std::size_t welds) {
        cut_weld_.assign(welds, false);
        if (elements_.cut_edges.empty()) return;
        for (std::size_t e = 0; e < size(); ++e)
            for (int k = 0; k < written_corners(e); ++k)
                if ((elements_.cut_edges[e] >> k) & 1u)
                    cut_weld_[weld(e, k)] = cut_weld_[weld(e, (k + 1) % corner_count(e))] = true;
    }

    /// Keeps, of set_[begin, end), the slots whose elements reach slot s's element by stepping
    /// between elements that share an edge at the vertex, none on a cut; in their order.
    void keep_reachable(int32_t s, std::size_t begin) {
        const std::vector<int32_t> candidates(set_.begin() + static_cast<std::ptrdiff_t>(begin), set_.end());
        std::vector<char> reached(candidates.size(), 0);
        for (std::size_t i = 0; i < candidates.size(); ++i) reached[i] = candidates[i] == s;
        auto joined = [&](int32_t a, int32_t b) {
            for (const EdgeAt& x : edges_at(a))
                for (const EdgeAt& y : edges_at(b))
                    if (x.far == y.far && !x.cut && !y.cut) return true;
            return false;
        };
        for (bool grew = true; grew;) {
            grew = false;
            for (std::size_t i = 0; i < candidates.size(); ++i)
                for (std::size_t j = 0; j < candidates.size() && !reached[i]; ++j)
                    if (reached[j] && joined(candidates[i], candidates[j])) reached[i] = grew = true;
        }
        set_.resize(begin);
        for (std::size_t i = 0; i < candidates.size(); ++i)
            if (reached[i]) set_.push_back(candidates[i]);
    }

    const Elements& elements_;
    const int32_t* material_;
    float cos_hard_;
    float tolerance_;  ///< weld tolerance
    std::vector<int32_t> weld_;
    std::vector<int32_t> incident_start_, incident_;
    std::vector<int32_t> set_start_, set_;
    std::vector<bool> border_;
    std::vector<bool> cut_weld_;  ///< welds at the end of a cut edge
};

/// The mean of `value_of(slot)` over the slots of S.
template <typename ValueOf>
Rgb set_mean(const Slots& slots, int32_t s, ValueOf value_of) {
    Rgb sum(0.0);
    for (const int32_t* t = slots.set_begin(s); t != slots.set_end(s); ++t) sum += value_of(*t);
    return sum / double(slots.set_end(s) - slots.set_begin(s));
}

Rgb mean_radiance(const Slots& slots, int32_t s, const std::vector<Rgb>& radiance) {
    return set_mean(slots, s, [&](int32_t t) { return radiance[Slots::element_of(t)]; });
}

/// Samples for a border slot's plane: element centres with their radiance, interior corners with
/// their step-1 value, each element and each vertex once.
struct Samples {
    std::vector<Vec3> position;
    std::vector<Rgb> value;
    std::vector<std::size_t> elements_taken;
    std::vector<int32_t> welds_taken;

    void add_element(const Elements& elements, const Slots& slots, std::size_t f, const std::vector<Rgb>& radiance,
                     const std::vector<Rgb>& corner_value) {
        if (std::find(elements_taken.begin(), elements_taken.end(), f) != elements_taken.end()) return;
        elements_taken.push_back(f);
        position.push_back(elements.centre[f]);
        value.push_back(radiance[f]);
        for (int k = 0; k < slots.corner_count(f); ++k) {
            const int32_t corner = Slots::slot(f, k), w = slots.weld(f, k);
            if (slots.border(corner) || std::find(welds_taken.begin(), welds_taken.end(), w) != welds_taken.end())
                continue;
            welds_taken.push_back(w);
            position.push_back(elements.vertices[elements.corners[f][k]]);
            value.push_back(corner_value[corner]);
        }
    }
};

/// Least-squares plane through the samples, evaluated at `at`; positions are measured in the plane
/// perpendicular to `normal`. Where the samples are collinear the gradient across their line is
/// taken as zero (the pseudo-inverse). Returns whether the samples determine the value at `at`:
/// they span the plane, or lie on one line through `at`.
bool fit_plane(const Samples& samples, const Vec3& at, const Vec3& normal, Rgb& out) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(normal));
    const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 t1 = glm::normalize(glm::cross(n, helper)), t2 = glm::cross(n, t1);
    const std::size_t count = samples.position.size();
    std::vector<glm::dvec2> x(count);
    glm::dvec2 x_mean(0.0);
    Rgb f_mean(0.0);
    for (std::size_t k = 0; k < count; ++k) {
        const glm::dvec3 d = glm::dvec3(samples.position[k]) - glm::dvec3(at);
        x[k] = glm::dvec2(glm::dot(d, t1), glm::dot(d, t2));
        x_mean += x[k] / double(count);
        f_mean += samples.value[k] / double(count);
    }
    double a = 0, b = 0, c = 0;  // covariance of positions [[a, b], [b, c]]
    Rgb gx(0.0), gy(0.0);        // covariance of position and value, per channel
    for (std::size_t k = 0; k < count; ++k) {
        const glm::dvec2 d = x[k] - x_mean;
        a += d.x * d.x;
        b += d.x * d.y;
        c += d.y * d.y;
        gx += d.x * (samples.value[k] - f_mean);
        gy += d.y * (samples.value[k] - f_mean);
    }
    const double trace = a + c, det = a * c - b * b;
    Rgb grad_x(0.0), grad_y(0.0);
    bool determined = true;
    // Samples spread across their main line by less than 3% of its length (a strip one element
    // wide, tapering: a sliver's rows) do not tell the gradient across it: taken as collinear.
    if (det > 1e-3 * trace * trace) {
        grad_x = (c * gx - b * gy) / det;
        grad_y = (a * gy - b * gx) / det;
    } else if (trace > 0.0) {  // rank one: the samples lie along u
        const glm::dvec2 u = glm::normalize(a >= c ? glm::dvec2(a, b) : glm::dvec2(b, c));
        const Rgb along = (u.x * gx + u.y * gy) / trace;
        grad_x = u.x * along;
        grad_y = u.y * along;
        const double off_line = std::abs(u.x * x_mean.y - u.y * x_mean.x);
        determined = off_line <= 1e-3 * std::sqrt(trace / double(count));
    } else {
        determined = glm::length(x_mean) == 0.0;
    }
    out = f_mean - x_mean.x * grad_x - x_mean.y * grad_y;
    return determined;
}

/// Step 2: the plane through what S knows, evaluated at this slot's vertex. When S's samples leave
/// the value open (a lone triangle at a grid corner), the elements around S's corners join in.
Rgb extrapolate(const Elements& elements, const Slots& slots, int32_t s, const std::vector<Rgb>& radiance,
                const std::vector<Rgb>& value) {
    const std::size_t e = Slots::element_of(s);
    const Vec3& at = elements.vertices[elements.corners[e][Slots::corner_of(s)]];
    Samples samples;
    for (const int32_t* t = slots.set_begin(s); t != slots.set_end(s); ++t)
        samples.add_element(elements, slots, Slots::element_of(*t), radiance, value);
    Rgb out;
    if (fit_plane(samples, at, elements.normal[e], out)) return out;
    for (const int32_t* t = slots.set_begin(s); t != slots.set_end(s); ++t) {
        const std::size_t f = Slots::element_of(*t);
        for (int k = 0; k < slots.corner_count(f); ++k) {
            const int32_t corner = Slots::slot(f, k);
            for (const int32_t* g = slots.set_begin(corner); g != slots.set_end(corner); ++g)
                samples.add_element(elements, slots, Slots::element_of(*g), radiance, value);
        }
    }
    fit_plane(samples, at, elements.normal[e], out);
    return out;
}

/// Step 3: a vertex inside a compatible neighbour's edge (a T-vertex: a sliver cut into strips
/// next to an uncut triangle, neighbours subdivided with different counts) takes that edge's linear
/// colour at its place, so that both sides show one colour along the edge and no crack opens. The
/// vertex is found by walking from one end of the open edge (used by one element) along the open
/// edges of the other side to its far end; where the two sides' vertices interleave, nothing changes.
void join_hanging_vertices(const Elements& elements, const Slots& slots, std::vector<Rgb>& colour) {
    auto key = [](int32_t a, int32_t b) {
        return (uint64_t(uint32_t(std::min(a, b))) << 32) | uint32_t(std::max(a, b));
    };
    std::unordered_map<uint64_t, int> uses;
    for (std::size_t e = 0; e < slots.size(); ++e)
        for (int k = 0; k < slots.written_corners(e); ++k)
            ++uses[key(slots.weld(e, k), slots.weld(e, (k + 1) % slots.corner_count(e)))];
    auto open = [&](std::size_t e, int k) {
        return !slots.cut_edge(e, k) &&
               uses.at(key(slots.weld(e, k), slots.weld(e, (k + 1) % slots.corner_count(e)))) == 1;
    };
    const double tolerance = slots.tolerance();
    std::vector<std::pair<int32_t, double>> chain;  // hanging welds and their place along the edge
    for (std::size_t e = 0; e < slots.size(); ++e) {
        const int m = slots.corner_count(e);
        for (int k = 0; k < slots.written_corners(e); ++k) {
            if (!open(e, k)) continue;
            const int32_t end = slots.weld(e, (k + 1) % m);
            const glm::dvec3 from(elements.vertices[elements.corners[e][k]]);
            const glm::dvec3 along = glm::dvec3(elements.vertices[elements.corners[e][(k + 1) % m]]) - from;
            const double length2 = glm::dot(along, along);
            chain.clear();
            int32_t at = slots.weld(e, k);
            double t_at = 0.0;
            bool reached = false;
            while (!reached) {
                // The next vertex along the edge over the other side's open edges at `at`.
                int32_t next = -1;
                double t_next = 2.0;
                for (const int32_t* s = slots.incident_begin(at); s != slots.incident_end(at); ++s) {
                    const std::size_t f = Slots::element_of(*s);
                    if (f == e || !slots.compatible(e, f)) continue;
                    const int mf = slots.corner_count(f), kf = Slots::corner_of(*s);
                    for (const int j : {kf, (kf + mf - 1) % mf}) {  // f's two edges at `at`
                        if (!open(f, j)) continue;
                        const int far = j == kf ? (kf + 1) % mf : j;
                        const glm::dvec3 d = glm::dvec3(elements.vertices[elements.corners[f][far]]) - from;
                        const double t = glm::dot(d, along) / length2;
                        if (glm::length(d - t * along) > tolerance || !(t > t_at) || t >= t_next) continue;
                        next = slots.weld(f, far);
                        t_next = t;
                    }
                }
                if (next < 0 || (next != end && t_next >= 1.0)) break;
                reached = next == end;
                if (!reached) chain.emplace_back(next, t_next);
                at = next;
                t_at = t_next;
            }
            if (!reached) continue;
            const Rgb &c0 = colour[Slots::slot(e, k)], &c1 = colour[Slots::slot(e, (k + 1) % m)];
            for (const auto& [w, t] : chain)
                for (const int32_t* s = slots.incident_begin(w); s != slots.incident_end(w); ++s)
                    if (slots.compatible(e, Slots::element_of(*s))) colour[*s] = (1.0 - t) * c0 + t * c1;
        }
    }
}

}  // namespace

CornerColors interpolate_corners(const Elements& elements, const std::vector<Rgb>& radiance, const int32_t* material,
                                 float hard_edge_angle, const std::vector<Rgb>* corner_light) {
    const Slots slots(elements, material, hard_edge_angle);
    const std::size_t n = elements.size();
    std::vector<Rgb> value(4 * n, Rgb(0.0));
    for (std::size_t e = 0; e < n; ++e)  // step 1
        for (int k = 0; k < slots.written_corners(e); ++k) {
            const int32_t s = Slots::slot(e, k);
            if (!slots.border(s)) value[s] = mean_radiance(slots, s, radiance);
        }
    for (std::size_t e = 0; e < n; ++e)  // step 2
        for (int k = 0; k < slots.written_corners(e); ++k) {
            const int32_t s = Slots::slot(e, k);
            if (slots.border(s)) value[s] = extrapolate(elements, slots, s, radiance, value);
        }
    if (corner_light)
        for (std::size_t e = 0; e < n; ++e)
            for (int k = 0; k < slots.written_corners(e); ++k) {
                const int32_t s = Slots::slot(e, k);
                value[s] += set_mean(slots, s, [&](int32_t t) { return (*corner_light)[t]; });
            }

    CornerColors colors;
    colors.element_corner.resize(4 * n);
    for (std::size_t s = 0; s < 4 * n; ++s) colors.element_corner[s] = glm::max(value[s], Rgb(0.0));
    join_hanging_vertices(elements, slots, colors.element_corner);

    // Input corners: any slot on the element vertex holding the polygon's corner (all elements of
    // one polygon share its compatible set there, hence its value).
    std::vector<int32_t> vertex_slot(elements.vertices.size(), -1);
    for (std::size_t e = 0; e < n; ++e)
        for (int k = 0; k < slots.written_corners(e); ++k) vertex_slot[elements.corners[e][k]] = Slots::slot(e, k);
    colors.input_corner.assign(elements.corner_vertex.size(), Rgb(0.0));
    for (std::size_t c = 0; c < elements.corner_vertex.size(); ++c) {
        const int32_t v = elements.corner_vertex[c];
        if (v >= 0 && vertex_slot[v] >= 0) colors.input_corner[c] = colors.element_corner[vertex_slot[v]];
    }
    return colors;
}

void replace_corners(const Elements& elements, const int32_t* material, float hard_edge_angle,
                     const std::vector<Rgb>& slot_value, const std::vector<uint8_t>& known, CornerColors& colors) {
    const Slots slots(elements, material, hard_edge_angle);
    const std::size_t n = elements.size();
    colors.element_corner.resize(4 * n, Rgb(0.0));
    // An emitter's back side has no slot set and is not written (Slots::written_corners).
    for (std::size_t e = 0; e < n; ++e)
        for (int k = 0; k < slots.written_corners(e); ++k) {
            const int32_t s = Slots::slot(e, k);
            if (!known[s]) continue;
            Rgb sum(0.0);
            int count = 0;
            // Coplanar neighbours keep their own values: on a flat surface the light at a vertex
            // differs between faces only where it is discontinuous (a block's corner on a floor).
            for (const int32_t* t = slots.set_begin(s); t != slots.set_end(s); ++t)
                if (known[*t] &&
                    (*t == s ||
                     elements.corners[Slots::element_of(*t)][Slots::corner_of(*t)] == elements.corners[e][k] ||
                     glm::dot(elements.normal[Slots::element_of(*t)], elements.normal[e]) < 1.0f - 1e-5f)) {
                    sum += slot_value[*t];
                    ++count;
                }
            colors.element_corner[s] = glm::max(sum / double(count), Rgb(0.0));  // s is in its own set
        }
    colors.input_corner.resize(elements.corner_vertex.size(), Rgb(0.0));
    std::vector<int32_t> vertex_slot(elements.vertices.size(), -1);
    for (std::size_t e = 0; e < n; ++e)
        for (int k = 0; k < slots.written_corners(e); ++k) vertex_slot[elements.corners[e][k]] = Slots::slot(e, k);
    for (std::size_t c = 0; c < elements.corner_vertex.size(); ++c) {
        const int32_t v = elements.corner_vertex[c];
        if (v >= 0 && vertex_slot[v] >= 0 && known[vertex_slot[v]])
            colors.input_corner[c] = colors.element_corner[vertex_slot[v]];
    }
}

}  // namespace radiosity
