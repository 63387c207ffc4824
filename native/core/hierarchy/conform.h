/// @file conform.h
/// @brief A leaf with vertices on its edges, split into as few triangles and quads as can be
/// (internal; hierarchy/output.h).
#pragma once

#include "common/types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace radiosity::hr {

/// Splits convex polygons, each a leaf's corners and the vertices its finer neighbours put on
/// its edges, into triangles and quads whose corners are those vertices only: as few elements
/// as can be (each quad saves one), none with three corners on one line (no zero-area triangle,
/// no quad with a flat corner), and among such splits the one whose worst corner angle is
/// largest. Keeps its tables from one polygon to the next.
class LeafSplitter {
public:
    /// `points`: the polygon's vertices in order. `edges[i]`: bit k set when point i lies on the
    /// leaf's edge k (a corner: two bits), which is how three points are known to be on a line.
    /// Appends each element's corners as indices into `points`, in the polygon's winding
    /// ([3] = -1 for triangles).
    void split(const std::vector<Vec3>& points, const std::vector<uint8_t>& edges,
               std::vector<std::array<int32_t, 4>>& elements);

private:
    /// The best split of the sub-polygon i, i+1, ..., j closed by the chord j - i.
    struct Cell {
        int32_t count;  ///< elements; kNone if there is none without a degenerate element
        float worst;    ///< the largest |cos| of their corner angles (0 for none)
        int32_t k, l;   ///< the element on the chord: i, k, (l,) j; l < 0 for a triangle
    };

    Cell& cell(std::size_t i, std::size_t j) { return cells_[i * n_ + j]; }
    void consider(std::size_t i, std::size_t j, int32_t k, int32_t l, Cell& best);
    bool on_one_line(int32_t a, int32_t b, int32_t c) const {
        return ((*edges_)[a] & (*edges_)[b] & (*edges_)[c]) != 0;
    }
    float corner_cos(int32_t before, int32_t at, int32_t after) const;

    std::size_t n_ = 0;
    const std::vector<uint8_t>* edges_ = nullptr;
    std::vector<Vec3> directions_;  ///< unit vector from point a to point b at a n + b
    std::vector<Cell> cells_;
    std::vector<std::pair<int32_t, int32_t>> pending_;
};

}  // namespace radiosity::hr
