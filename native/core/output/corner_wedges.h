/// @file corner_wedges.h
/// @brief The light around the element corners on seams, by direction (internal; final_gather.h).
///
/// Where an occluder stands on a surface (a block on a floor), the shadow of its edge starts at the
/// vertex: next to the vertex the light depends on the direction from it, not on the distance, so
/// no one value at the vertex can stand for it. Yet the rays of the points beside it (the block's
/// own face at its foot) land within a hair of the vertex and read that one value. So each element
/// corner on a seam keeps a table of how much more light arrives a hair from the vertex, in kBins
/// directions across the corner's angle, than at the point the vertex's value was gathered at; a
/// ray landing in the element adds, for each such corner, the table at the landing point's
/// direction from the corner, weighted as the corner's colour is (bilinear): exact next to the
/// vertex, fading out across the element. Where the light does not turn with the direction (a
/// furnace), nothing changes.
#pragma once

#include "geometry/scene.h"

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace radiosity::detail {

class CornerWedges {
public:
    static constexpr int kBins = 16;

    /// Fills `table` (kBins values) for corner k of element e: how much more light (irradiance / pi)
    /// arrives at `points` than at the point the vertex's value was gathered at.
    using FillTable = std::function<void(std::size_t e, int k, const Vec3* points, Rgb* table)>;

    /// Tables for the corners of elements at the element vertices marked in `on_seam`, computed
    /// `parallel` over the corners (a runner of (count, body(index)), the gather's parallel_rows).
    template <typename Parallel>
    CornerWedges(const Elements& elements, const std::vector<uint8_t>& on_seam, float scene_size, const FillTable& fill,
                 const Parallel& parallel);
    CornerWedges() = default;

    bool empty() const { return values_.empty(); }

    /// What the light around the hit element's corners adds to the radiance read at (u, v) (the
    /// ray tracer's parameters, as radiance_near blends the corners): reflectance x the sum over its
    /// corners with a table of weight x the table at the point's direction.
    Rgb correction(const Elements& elements, std::size_t element, float u, float v) const;
    /// The same read as weights: appends each table value correction() reads (by the index
    /// reflected_entry() takes) with its weight, before the reflectance, to `terms`.
    void terms(const Elements& elements, std::size_t element, float u, float v,
               std::vector<std::pair<int32_t, double>>& terms) const;
    /// A table value, by the index terms() gives, times the reflectance of its table's element.
    Rgb reflected_entry(const Elements& elements, std::size_t index) const {
        return elements.reflectance[std::size_t(element_of_table_[index / kBins])] * values_[index];
    }
    /// Table values in all.
    std::size_t entries() const { return values_.size(); }

private:
    /// The point a hair from corner k of element e, at parametric angle s in [0, 1] across its corner.
    Vec3 point_at(const Elements& elements, std::size_t e, int k, double s) const;
    void fill_table(const Elements& elements, std::size_t slot, const FillTable& fill);
    /// Calls visit(low, low weight, high, high weight) for each corner of `element` with a table:
    /// the two bins around the point's direction from the corner and their weights (the corner's
    /// blend weight at (u, v), split linearly between the bins' centres).
    template <typename Visit>
    void visit_terms(const Elements& elements, std::size_t element, float u, float v, const Visit& visit) const;

    std::vector<int32_t> table_of_slot_;  ///< slot 4 e + k -> its first value, or -1
    std::vector<Rgb> values_;             ///< kBins values per table, at parametric angles (i + 0.5) / kBins
    std::vector<int32_t> element_of_table_;
    float scene_size_ = 0.0f;
};

template <typename Parallel>
CornerWedges::CornerWedges(const Elements& elements, const std::vector<uint8_t>& on_seam, float scene_size,
                           const FillTable& fill, const Parallel& parallel)
    : table_of_slot_(4 * elements.size(), -1), scene_size_(scene_size) {
    std::vector<std::size_t> slots;
    for (std::size_t e = 0; e < elements.size(); ++e) {
        if (elements.is_back(e)) continue;  // not written, so no corner colours to correct
        for (int k = 0; k < elements.corner_count(e); ++k)
            if (on_seam[std::size_t(elements.corners[e][k])]) {
                table_of_slot_[4 * e + std::size_t(k)] = int32_t(slots.size() * kBins);
                slots.push_back(4 * e + std::size_t(k));
            }
    }
    values_.resize(slots.size() * kBins);
    for (const std::size_t slot : slots) element_of_table_.push_back(int32_t(slot / 4));
    parallel(slots.size(), [&](std::size_t t) { fill_table(elements, slots[t], fill); });
}

}  // namespace radiosity::detail
