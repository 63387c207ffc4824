/// @file output.h
/// @brief The leaves of hierarchical radiosity as a mesh without cracks (internal).
#pragma once

#include "hierarchy/tree.h"

namespace radiosity::hr {

struct LeafMesh {
    Elements elements;           ///< one element per leaf, or a few triangles and quads (see below)
    std::vector<Rgb> radiance;   ///< per element: its leaf's radiance
    std::vector<Rgb> lamp_part;  ///< per element: the part of that radiance the lamps gave, rho G_lamps
    std::vector<int32_t> leaf;   ///< per element: its leaf's node (a split leaf's elements follow each other)
    std::size_t leaves = 0;
};

/// Every leaf, with the vertices its finer neighbours put on its edges: a leaf without any keeps
/// its corners; one with some is split into triangles and quads whose corners are its corners
/// and those vertices (hierarchy/conform.h: as few as can be, none degenerate, no new vertex), so that
/// neighbours share every vertex on their common edge (no T-vertices). Input corners map to the
/// welded patch vertices (Elements::corner_vertex), so original meshes get their colours too.
/// Elements::emission holds E + rho G_lamps (`lamp_light`, per node): the lamps' first
/// reflection counts as emitted light, as bake() counts it. Progress phase "output" (done =
/// patches written); throws Cancelled.
LeafMesh leaf_mesh(const Tree& tree, const BuildResult& build, const std::vector<Rgb>& lamp_light,
                   const ProgressFn& progress);

}  // namespace radiosity::hr
