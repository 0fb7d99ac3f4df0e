#pragma once
// What the hybrid filter (hybrid.cpp) does to the filtered signal between the wavelet levels, so
// that a piecewise smooth signal (curvature at the creases of a CAD part, heights at the edges of
// buildings) comes back without overshoot or saw teeth (docs/algorithms.md#hybrid-filter).
#include <vector>

#include "geoshift/mean_shift.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift::hybrid_detail {

// The coarse signal the mean shift filters: per coarse vertex, the mean of the input rows of the
// fine vertices collapsed into it (itself included), weighted by their area and by a Gaussian of
// how far their input values are from its own, in units of each channel's h_r (an edge-aware
// restriction). LOCAAT's lifted signal (mr.coarseAttributes) is not a convex combination: next to
// a jump its update f_e += u_eo d_o overshoots (the absolute curvature of a box went to -4.4 beside
// its creases, for values in [0, 37]), and a crease vertex that keeps its value loses part of it to
// the flat neighbours collapsed into it; the mean shift then keeps both as modes of their own.
// Euclidean channels only; UnitVector rows are the lifted ones. `input` holds the channels the
// analysis lifted, per fine vertex.
AttributeSet edgeAwareCoarseSignal(const Multiresolution& mr, const AttributeSet& input, const MeanShiftOptions& options);

// The filtered coarse rows on every fine vertex with the details dropped (alpha = 0), level by
// level from the coarsest: an odd vertex takes the mean of its even neighbours weighted by the
// prediction weights times a Gaussian of how far their *input* values are from its own, in units
// of each channel's h_r (joint bilateral upsampling, Kopf et al. 2007). The geometric prediction
// alone averages across a crease: an odd vertex on a crease, predicted from two crease neighbours
// and four flat ones, drops to a third of the crease's value, one vertex in two along every crease.
// When every weight underflows (no even neighbour within ~7 h_r, as a crease vertex the decimation
// left among flat ones), the vertex is read the same way from its fine 1-ring once the rest is
// known; an outlier unlike all of those takes its closest known neighbour. Weights are
// non-negative and sum to one, so each output lies in the range of the coarse values. UnitVector
// rows are re-normalised.
AttributeSet guidedProlongation(const Multiresolution& mr, const AttributeSet& coarse, const AttributeSet& input,
                                const MeanShiftOptions& options);

}  // namespace geoshift::hybrid_detail
