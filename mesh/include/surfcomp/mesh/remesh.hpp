// Isotropic remeshing of a triangle surface (CGAL Polygon Mesh Processing adapter).
#pragma once

#include "surfcomp/mesh/surface.hpp"

namespace surfcomp::mesh {

/// The edge length L of an equilateral triangle mesh with `vertex_density` vertices per A^2.
/// A closed mesh of genus 0 has F = 2V - 4 triangles, so for many vertices F ~ 2V and
/// area = F * (sqrt(3)/4) L^2 = V * (sqrt(3)/2) L^2, hence L = sqrt(2 / (sqrt(3) * density)).
/// Returns A (0.680 A for 2.5 vertices/A^2). Throws OptionError unless density is finite and > 0.
double edge_length_for_density(double vertex_density);

/// Remeshes `input` (closed or open, 2-manifold triangles) so that its edges are close to
/// `target_edge_length` (A): split edges longer than 4/3 L, collapse edges shorter than 4/5 L,
/// flip edges towards valence 6 and relax tangentially; `iterations` rounds (Botsch & Kobbelt
/// 2004, "A remeshing approach to multiresolution modeling";
/// CGAL::Polygon_mesh_processing::isotropic_remeshing). With `project_to_input` the vertices
/// are projected back onto the input triangles after each round; a caller that projects onto
/// an exact surface afterwards (build_ses) can skip that. Sequential and deterministic. The
/// result has no normals and no vertex properties; its source() is the input's. Throws
/// OptionError for L not finite or <= 0 or iterations < 1, TopologyError for an empty input
/// or one that is not 2-manifold.
Surface isotropic_remesh(const Surface& input, double target_edge_length, int iterations = 3,
                         bool project_to_input = true);

}  // namespace surfcomp::mesh
