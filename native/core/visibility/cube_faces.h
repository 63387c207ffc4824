/// @file cube_faces.h
/// @brief The faces of the hemi-cube and the full cube: frames, cell layout and cell centres (internal).
///
/// Local coordinates (u, v, w): w is the hemi-cube's normal. Each face is a rotation of the local
/// frame, face coordinates (x, y, z) with the face on the plane z = 1 and x, y in [-1, 1]; cells are
/// indexed face-major, then row (y), then column (x). Sides of the hemi-cube keep only their upper
/// half, y = w in [0, 1].
#pragma once

#include "common/types.h"

#include <array>

namespace radiosity::cube {

/// One face: face coordinate k is sign[k] * local[axis[k]]. Every face frame is a rotation
/// (determinant +1), so cross products map face-wise like vectors.
struct Face {
    std::array<int, 3> axis;
    std::array<float, 3> sign;
};

/// Top (+w), +u, -u, +v, -v, bottom (-w). The sides have y = w.
inline constexpr std::array<Face, 6> faces{{
    {{0, 1, 2}, {1, 1, 1}},
    {{1, 2, 0}, {1, 1, 1}},
    {{1, 2, 0}, {-1, 1, -1}},
    {{0, 2, 1}, {-1, 1, 1}},
    {{0, 2, 1}, {1, 1, -1}},
    {{0, 1, 2}, {1, -1, -1}},
}};

/// Cell rows and columns of the faces of one render.
struct Layout {
    int resolution = 0;  ///< columns per face
    int face_count = 0;  ///< 5 (hemisphere) or 6 (sphere)
    bool hemisphere = true;

    int rows(int face) const { return hemisphere && face > 0 ? resolution / 2 : resolution; }
    /// y of the lower edge of row 0.
    float y_min(int face) const { return hemisphere && face > 0 ? 0.0f : -1.0f; }
    std::size_t offset(int face) const {
        const std::size_t n = resolution;
        if (!hemisphere || face == 0) return face * n * n;
        return n * n + (face - 1) * n * (n / 2);
    }
    std::size_t cells() const { return offset(face_count); }
    float cell_size() const { return 2.0f / resolution; }
};

inline Layout hemisphere_layout(int resolution) { return {resolution, 5, true}; }
inline Layout sphere_layout(int resolution) { return {resolution, 6, false}; }

/// Face coordinates of a local vector.
inline Vec3 to_face(const Face& f, const Vec3& local) {
    return {f.sign[0] * local[f.axis[0]], f.sign[1] * local[f.axis[1]], f.sign[2] * local[f.axis[2]]};
}

/// Local vector of face coordinates.
inline Vec3 to_local(const Face& f, const Vec3& face) {
    Vec3 local;
    for (int k = 0; k < 3; ++k) local[f.axis[k]] = f.sign[k] * face[k];
    return local;
}

}  // namespace radiosity::cube
