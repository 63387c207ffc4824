/// @file hemicube.h
/// @brief Item-buffer rendering of elements onto a hemi-cube (or a full cube) around a point.
///
/// The hemi-cube (Cohen & Greenberg 1985): its five faces are N x N (top) and N x N/2 (sides) cells, each
/// with a delta form factor computed once per resolution. Every element is projected onto the
/// faces it overlaps with a z-buffer, so each cell ends up naming the nearest visible element.
/// Summing the cells' weights per element gives one row of form factors.
#pragma once

#include "common/sparse.h"
#include "geometry/scene.h"

#include <memory>
#include <vector>

namespace radiosity {

/// Cell weights for one resolution, computed once and shared read-only between threads.
/// Cells are indexed as the item buffer is: face-major, then row, then column.
struct CubeWeights {
    int resolution = 0;              ///< cells per full face edge, even
    std::vector<float> form_factor;  ///< hemi-cube: exact delta form factors, sum 1 (to 1e-6)
    std::vector<float> solid_angle;  ///< full cube: cell solid angles, sum 4 pi
    static std::shared_ptr<const CubeWeights> make(int resolution);
};

/// One per thread: owns the z-buffer and item buffer.
class Hemicube {
public:
    explicit Hemicube(std::shared_ptr<const CubeWeights> weights);
    ~Hemicube();
    Hemicube(Hemicube&&) noexcept;
    Hemicube& operator=(Hemicube&&) noexcept;

    /// Renders `elements` seen from `origin` over the hemisphere around `normal` (five faces).
    /// Element `exclude` (or -1) is not drawn. Polygons behind the plane are culled; elements
    /// seen from their back side occlude but are credited to nobody.
    void render_hemisphere(const Elements& elements, const Vec3& origin, const Vec3& normal, int32_t exclude);
    /// As above, with the hemi-cube turned by `angle` radians about the normal (for averaging
    /// several orientations against aliasing).
    void render_hemisphere(const Elements& elements, const Vec3& origin, const Vec3& normal, int32_t exclude,
                           float angle);

    /// Renders `elements` seen from `origin` in all directions (six full faces).
    void render_sphere(const Elements& elements, const Vec3& origin, int32_t exclude);

    /// Sums `cell_weight` per element over the last render into `row` (columns ascending).
    /// Pass weights().form_factor after render_hemisphere for a form-factor row.
    void accumulate(const std::vector<float>& cell_weight, SparseRow& row);

    /// Element visible through each cell of the last render (-1 for none); for tests and tools.
    const std::vector<int32_t>& item_buffer() const;
    /// Unit direction through the centre of cell `cell` of the last render, world space.
    Vec3 cell_direction(std::size_t cell) const;
    /// Distance from the origin of the last render to the nearest drawn polygon along
    /// cell_direction(cell), from the z-buffer (occluders included); infinity where nothing was drawn.
    float cell_distance(std::size_t cell) const;

    const CubeWeights& weights() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace radiosity
