/// @file zonal.h
/// @brief Exchange factors of the zonal method (seed 002) in gathering form: one row per surface
/// element and per zone, over all of them.
///
/// Unknowns are numbered elements first (0 .. n-1), then zones (n .. n+z-1). Row x holds, for every
/// receiver y, the fraction R_xy of the light leaving x that y takes up (per RGB channel):
///  - element i (hemi-cube at its centre, cell weights dF_p): the visible element j gets
///    dF_p * tau along the cell's ray up to j (Rushmeier & Torrance 1987's S_iS_j / A_i), every zone k crossed gets
///    dF_p * its credited fraction (S_iV_k / A_i);
///  - zone k (full cube, cell weights solid angle / 4 pi): the same walk, but each cell's ray starts
///    at its own point inside the zone, spread over its whole block by a low-discrepancy sequence, so
///    the zone's own extinction of its light is counted: V_kV_k > 0, and adjacent and optically thick
///    zones stay accurate where the point formula for volume-to-volume factors fails (test_volume_zonal.cpp).
///    Surfaces are found by the cube's item buffer from the zone's centre; each ray's distance to
///    that element is measured from its own start point (to the element's plane).
/// Because the walk conserves energy per ray, a row sums to the fraction of the cells that see
/// something: 1 in a closed enclosure. Gathering reads rows as they are: L_x = E_x + a_x sum R_xy L_y
/// (zonal_solver.h). The zonal method's reciprocity w_x R_xy = w_y R_yx (w as there) holds only
/// approximately for rows rendered from both ends; enforce_reciprocity() makes it exact.
#pragma once

#include "media/transmittance.h"
#include "visibility/hemicube.h"

#include <vector>

namespace radiosity {

/// One row: receivers ascending, a fraction per channel.
struct ZonalRow {
    std::vector<int32_t> col;
    std::vector<Channels> val;
    void clear() {
        col.clear();
        val.clear();
    }
};

/// All rows in CSR. Grey media (K_t the same in all channels everywhere) give the same fraction in
/// every channel, stored once (`channels` = 1); otherwise three floats per nonzero.
struct ZonalMatrix {
    int channels = 1;
    std::vector<int64_t> row_start{0};
    std::vector<int32_t> col;
    std::vector<float> val;  ///< `channels` values per nonzero

    std::size_t rows() const { return row_start.size() - 1; }
    std::size_t nonzeros() const { return col.size(); }
    std::size_t bytes() const {
        return row_start.size() * sizeof(int64_t) + col.size() * sizeof(int32_t) + val.size() * sizeof(float);
    }
    Rgb value(std::size_t nonzero) const {
        if (channels == 1) return Rgb(val[nonzero]);
        return Rgb(val[3 * nonzero], val[3 * nonzero + 1], val[3 * nonzero + 2]);
    }
};

struct ZonalFactorSettings {
    int surface_resolution = 128;  ///< hemi-cube cells per face edge at elements (as BakeSettings::resolution)
    int zone_resolution = 32;      ///< full-cube cells per face edge at zones: 6 N^2 rays per zone
    /// Memory allowed for the stored rows; compute_exchange_factors throws InputError beyond it.
    std::size_t budget_bytes = std::size_t(2) << 30;
};

/// Renders single rows; one per thread (owns its cubes and accumulators).
class ZonalRowRenderer {
public:
    ZonalRowRenderer(const Elements& elements, const Zones& zones, const MediumTracer& tracer,
                     const ZonalFactorSettings& settings);
    /// Row of unknown x (element x < n, zone x - n otherwise).
    void row(int32_t x, ZonalRow& out);

private:
    void add_cell(int32_t item, double weight, const Channels& tau);
    const Elements& elements_;
    const Zones& zones_;
    const MediumTracer& tracer_;
    Hemicube surface_cube_, zone_cube_;
    std::vector<glm::dvec3> sum_;
    std::vector<int32_t> touched_;
    std::vector<ZoneCredit> credits_;
};

/// R^T in CSR, same channel layout: row x holds column x of R, rows ascending.
ZonalMatrix transpose(const ZonalMatrix& R);

/// Makes R reciprocal, w_x R_xy = w_y R_yx exactly, keeping every row's sum (1 in a closed scene,
/// less where light escapes): the exchanges S_xy = w_x R_xy measured from both ends are averaged,
/// S = (S + S^T) / 2, then scaled symmetrically, S_xy -> d_x S_xy d_y, until the rows sum as before
/// (symmetric Sinkhorn-Knopp, to 1e-9). Without it, centre-point hemi-cubes (about 1% off next to
/// shared edges) and sampled zone rows leave the solved scene about 0.5% out of energy balance.
/// `w` per unknown: element area, zone 4 K_t V (Zones::weight). Rows of zero weight stay as they are.
void enforce_reciprocity(ZonalMatrix& R, const std::vector<Rgb>& w);

/// Every row, in parallel (TBB). Progress phase "form_factors" (done = rows); throws Cancelled,
/// and InputError when the rows outgrow settings.budget_bytes (zones^2 growth: larger voxels help).
ZonalMatrix compute_exchange_factors(const Elements& elements, const std::vector<Medium>& media, const Zones& zones,
                                     const ZonalFactorSettings& settings, const ProgressFn& progress = {});

}  // namespace radiosity
