/// @file row_renderer.h
/// @brief One form-factor row per call: hemi-cube(s) at the element's centre, then the optional
/// corrections of issue 5 (orientation averaging against aliasing, near-field factors).
#pragma once

#include "radiosity/hemicube.h"
#include "radiosity/near_field.h"

namespace radiosity {

/// How rows are computed. The defaults give the plain hemi-cube row of the seed.
struct RowSettings {
    int resolution = 128;  ///< hemi-cube cells per full face edge
    /// Hemi-cubes per row, each turned about the normal by a further 1/rotations of a quarter
    /// turn (plus a per-element offset), averaged: small or distant elements that fall between
    /// cell centres in one orientation are caught in others. Costs `rotations` renders per row.
    int rotations = 1;
    NearFieldSettings near_field;
};

/// Renders rows; one per thread (owns a hemi-cube and scratch space).
class RowRenderer {
public:
    RowRenderer(std::shared_ptr<const CubeWeights> weights, const RowSettings& settings);
    /// Row i of F (columns ascending).
    void row(const Elements& elements, int32_t i, SparseRow& out);

private:
    Hemicube hemicube_;
    RowSettings settings_;
    SparseRow turn_;
    std::vector<double> sum_;
    std::vector<int32_t> touched_;
};

}  // namespace radiosity
