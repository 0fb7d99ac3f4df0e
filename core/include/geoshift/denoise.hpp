#pragma once
// Mesh denoising by Riemannian mean shift on vertex normals (the paper's §4.1; ALGORITHMS.md §0.4):
// passes of [mean shift of the vertex normals with the kernel of eq. 8 → face normals → vertex
// update], with log and exp maps on a Taubin-smoothed copy of the input (the support).
#include <vector>

#include "geoshift/mean_shift.hpp"
#include "geoshift/smoothing.hpp"
#include "geoshift/vertex_update.hpp"
#include "geoshift/wavelet.hpp"

namespace geoshift {

// How a face's target normal comes from its three filtered vertex normals.
enum class FaceNormalRule {
  Mean,       // the paper's: their normalised mean. A face beside a crease averages the two sides
              // its corners took and the crease is bevelled (about 45° off on a box).
  Consensus,  // their mean weighted by agreement with the face's own normal,
              // exp(−|n_k − n_f|² / 2h_r²): a corner that took the other side of a crease drops out.
};

struct DenoiseOptions {
  int passes = 3;
  FaceNormalRule faceNormals = FaceNormalRule::Consensus;
  // Bandwidth of the consensus weights (chord length between unit normals); 0: the mean shift's h_r.
  double consensusBandwidth = 0.25;
  // The mean shift of the normals. Defaults are the paper's: r = 4 AEL, h_s = 3 AEL, h_r = 0.45,
  // k_max = 50, ε = AEL/5, kernel eq. 8 (set by denoise(); `channels` is ignored).
  MeanShiftOptions meanShift = paperMeanShift();
  TaubinOptions support;            // smoothing of the support copy (MeshLab's 10 λ|μ steps)
  // Hybrid denoising (Algorithm 2 on positions): analyse `levels` wavelet levels, denoise the coarse
  // mesh, synthesise with detail gain `alpha` (one for all levels or one per level; 0 drops the
  // fine details with their noise). The no-flip guarantee then holds on the coarse mesh.
  int levels = 0;
  std::vector<double> alpha = {0};
  WaveletOptions wavelet;
  VertexUpdateOptions vertexUpdate; // 20 iterations, no face ever flipped relative to the input

  static MeanShiftOptions paperMeanShift() {
    MeanShiftOptions o;
    o.spatialBandwidth = 3;
    o.radius = 4;
    o.rangeBandwidth = 0.45;
    o.rangeKernel = RangeKernel::NormalSimilarity;
    o.maxIterations = 50;
    o.epsilon = 0.2;
    // The paper's range update: on the evaluation (README, `npm run eval`) it beats the joint
    // update on every Fandisk case (RMS 0.30 vs 0.39 ×10² at 0.5 AEL noise), whose eq. 8 kernel lets
    // normals average across creases.
    o.rangeUpdate = RangeUpdate::Sampled;
    return o;
  }
};

struct DenoiseResult {
  double meanIterations = 0;     // of the mean shift, per vertex per pass
  double convergedFraction = 0;  // of the last pass
  int limitedSteps = 0;          // vertex-update steps the flip guard shortened, all passes
  int threads = 1;
  int filteredVertices = 0;      // the mesh's, or the coarse mesh's with levels > 0
  double seconds = 0;
};

// Moves the mesh's vertices. Throws InputError on bad options (as meanShift, taubinSmooth and
// updateVertices do, or passes < 1) and on a mesh without faces; Cancelled through `progress`,
// leaving the mesh as it was.
DenoiseResult denoise(Mesh& mesh, const DenoiseOptions& options = {}, const Progress& progress = {});

}  // namespace geoshift
