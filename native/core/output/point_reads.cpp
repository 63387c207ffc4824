/// @file point_reads.cpp
/// @brief A gathered point's reads as weights on the values read (point_reads.h).
#include "output/point_reads.h"

#include "output/corner_blend.h"

#include <algorithm>
#include <cmath>

namespace radiosity::detail {
namespace {

using Source = PointReads::Source;

/// A term's weights while one point is folded, in double precision; `near`: its weight read near the point.
struct Folded {
    double sum = 0.0, difference = 0.0, near = 0.0;
    glm::dvec2 rotation{0.0}, translation{0.0};
};

/// Where each value read has its term while one point is folded: one table per source, -1 where
/// none; only the entries touched are reset, so a point costs its rays, not the scene's size.
class TermIndex {
public:
    void prepare(const Elements& elements, const CornerWedges* wedges) {
        const std::size_t n = elements.size();
        offset_ = {0, 5 * n, 6 * n, 6 * n + (wedges != nullptr ? wedges->entries() : 0)};
        const std::size_t size = offset_[3] + n;
        if (position_.size() < size) position_.resize(size, -1);
        read_.clear();
        folded_.clear();
    }
    /// The weights of the value `index` from `source`, added if new.
    Folded& term(Source source, std::size_t index) {
        int32_t& at = position_[offset_[std::size_t(source)] + index];
        if (at < 0) {
            at = int32_t(read_.size());
            touched_.push_back(&at);
            read_.push_back((uint32_t(source) << PointReads::Term::kIndexBits) | uint32_t(index));
            folded_.emplace_back();
        }
        return folded_[std::size_t(at)];
    }
    /// The terms folded, into `reads` (with their gradients' weights if `gradients`), and the field
    /// slots read near the point, in order, their weights divided by the rays; ready for the next point.
    void finish(PointReads& reads, bool gradients) {
        for (int32_t* at : touched_) *at = -1;
        touched_.clear();
        reads.terms.reserve(read_.size());
        for (std::size_t t = 0; t < read_.size(); ++t) {
            const Folded& f = folded_[t];
            reads.terms.push_back({read_[t], float(f.sum), float(f.difference)});
            if (gradients) reads.gradients.push_back({glm::vec2(f.rotation), glm::vec2(f.translation)});
            if (f.near != 0.0)
                reads.near_slots.emplace_back(int32_t(reads.terms.back().index()), f.near / double(reads.rays));
        }
        std::sort(reads.near_slots.begin(), reads.near_slots.end());
    }

private:
    std::array<std::size_t, 4> offset_{};
    std::vector<int32_t> position_;
    std::vector<int32_t*> touched_;
    std::vector<uint32_t> read_;
    std::vector<Folded> folded_;
};

/// One front hit's weights on what it reads besides the sum's: the halves' sign and its gradients'
/// weights (null: not folded).
struct RayWeights {
    double difference;
    const glm::dvec2* rotation;
    const glm::dvec2* translation;
};

/// Adds `weight` of the value `value` from `source`, read by `ray`; returns its term.
Folded& add(TermIndex& index, Source source, std::size_t value, double weight, const RayWeights& ray) {
    Folded& term = index.term(source, value);
    term.sum += weight;
    term.difference += weight * ray.difference;
    if (ray.rotation != nullptr) {
        term.rotation += weight * *ray.rotation;
        term.translation += weight * *ray.translation;
    }
    return term;
}

/// Whether element e may have an emission of its own: an emitting polygon's (it has a twin), a
/// lamp's, or one that emits now (`emitted`). Whether a face emits is part of the geometry a fold is
/// kept for (a face that starts or stops emitting makes a new one), so any other element's emission
/// stays 0 and its term is left out.
bool may_emit(const Elements& elements, const std::vector<Rgb>& emitted, std::size_t e) {
    return elements.has_twin(e) || !elements.blocks(e) || max_channel(emitted[e]) > 0.0;
}

/// Adds one front hit's reads: the field's corner slots and, with `bubbles`, its bubble (or a back
/// side's solved value), the wedge tables' values, less its emission; the corner slots read near the
/// point (`near`) also as such (a bubble is 0 there, and the near reads' solve does not write it).
void fold_front_hit(const Elements& elements, const std::vector<Rgb>& emitted, const CornerWedges* wedges,
                    const hr::Visibility::Hit& hit, bool near, bool bubbles, const RayWeights& ray, TermIndex& index) {
    const std::size_t h = std::size_t(hit.patch);
    if (elements.is_back(h)) {
        add(index, Source::BackRadiance, h, 1.0, ray);
    } else {
        const std::array<double, 4> w = corner_weights(elements, h, hit.u, hit.v);
        for (int k = 0; k < elements.corner_count(h); ++k) {
            Folded& term = add(index, Source::FieldSlot, 4 * h + std::size_t(k), w[std::size_t(k)], ray);
            if (near) term.near += w[std::size_t(k)];
        }
        if (bubbles)
            add(index, Source::FieldSlot, bubble_slot(elements, h), element_bubble(elements, h, hit.u, hit.v), ray);
    }
    if (wedges != nullptr) {
        thread_local std::vector<std::pair<int32_t, double>> table;
        table.clear();
        wedges->terms(elements, h, hit.u, hit.v, table);
        for (const auto& [entry, weight] : table) add(index, Source::Wedge, std::size_t(entry), weight, ray);
    }
    if (may_emit(elements, emitted, h)) add(index, Source::Emitted, h, -1.0, ray);
}

}  // namespace

std::size_t PointReads::bytes() const {
    return terms.capacity() * sizeof(Term) + gradients.capacity() * sizeof(GradientTerm) +
           back_distances.capacity() * sizeof(float) + near_slots.capacity() * sizeof(near_slots[0]) +
           sizeof(PointReads);
}

PointReads fold_reads(const Elements& elements, const std::vector<Rgb>& emitted, const CornerWedges* wedges,
                      const RayGrid& grid, const std::vector<RayHit>& hits) {
    PointReads reads;
    reads.rays = int(hits.size());
    std::vector<double> inverse(hits.size(), 0.0);
    for (std::size_t i = 0; i < hits.size(); ++i)
        if (hits[i].hit.patch >= 0 && hits[i].hit.distance > 0.0f) inverse[i] = 1.0 / double(hits[i].hit.distance);
    const GradientWeights gradient = grid.gradients ? gradient_weights(grid.grid, inverse) : GradientWeights{};
    thread_local TermIndex index;
    index.prepare(elements, wedges);
    for (std::size_t i = 0; i < hits.size(); ++i) {
        const hr::Visibility::Hit& hit = hits[i].hit;
        if (hit.patch < 0) continue;
        if (!hits[i].front) {
            reads.back_distances.push_back(hit.distance);
            continue;
        }
        const bool near = hit.distance < grid.near * std::sqrt(elements.area[std::size_t(hit.patch)]);
        reads.near_hits += near;
        const RayWeights ray{half_sign(int(i), grid.grid), grid.gradients ? &gradient.rotation[i] : nullptr,
                             grid.gradients ? &gradient.translation[i] : nullptr};
        fold_front_hit(elements, emitted, wedges, hit, near && !elements.is_back(std::size_t(hit.patch)), grid.bubbles,
                       ray, index);
    }
    index.finish(reads, grid.gradients);
    reads.back_distances.shrink_to_fit();
    return reads;
}

namespace {

Rgb value_of(const PointReads::Term& term, const ReadValues& values) {
    const std::size_t i = term.index();
    switch (term.source()) {
        case Source::FieldSlot:
            return values.field[i];
        case Source::BackRadiance:
            return values.radiance[i];
        case Source::Wedge:
            return values.wedges->reflected_entry(values.elements, i);
        case Source::Emitted:
            return values.emitted[i];
    }
    return Rgb(0.0);
}

}  // namespace

ReadSums evaluate(const PointReads& reads, const ReadValues& values) {
    ReadSums out;
    const bool gradients = !reads.gradients.empty();
    for (std::size_t t = 0; t < reads.terms.size(); ++t) {
        const PointReads::Term& term = reads.terms[t];
        const Rgb v = value_of(term, values);
        out.sum += double(term.sum) * v;
        out.difference += double(term.difference) * v;
        if (values.probe != nullptr && term.source() == Source::FieldSlot && term.index() < values.probe->size())
            out.probe += double(term.sum) * (*values.probe)[term.index()];
        if (!gradients) continue;
        const glm::dvec2 rotation(reads.gradients[t].rotation), translation(reads.gradients[t].translation);
        for (std::size_t c = 0; c < 3; ++c) {
            out.gradients.rotation[c] += v[int(c)] * rotation;
            out.gradients.translation[c] += v[int(c)] * translation;
        }
    }
    out.rest = out.sum;
    for (const auto& [slot, weight] : reads.near_slots) out.rest -= (weight * double(reads.rays)) * values.field[slot];
    return out;
}

}  // namespace radiosity::detail
