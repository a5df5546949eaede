#include "surfcomp/molsurf/molecular_surface.hpp"

#include "surfcomp/core/error.hpp"

namespace surfcomp::molsurf {

AtomBalls atom_balls(const Molecule& molecule) {
  const auto n = static_cast<Eigen::Index>(molecule.atoms.size());
  AtomBalls balls{Eigen::MatrixX3d(n, 3), Eigen::VectorXd(n)};
  for (Eigen::Index i = 0; i < n; ++i) {
    const Atom& atom = molecule.atoms[static_cast<std::size_t>(i)];
    balls.centers.row(i) = atom.position.transpose();
    balls.radii(i) = atom.radius;
  }
  return balls;
}

mesh::Surface build_molecular_surface(const Molecule& molecule,
                                      const MolecularSurfaceOptions& options) {
  validate_molecule(molecule);
  const AtomBalls balls = atom_balls(molecule);
  mesh::Surface surface = build_ses(balls.centers, balls.radii, options.ses, molecule.source);
  mesh::require_closed_manifold(surface);
  assign_surface_properties(surface, &molecule, options);
  return surface;
}

void assign_surface_properties(mesh::Surface& surface, const Molecule* molecule,
                               const MolecularSurfaceOptions& options) {
  if (surface.n_faces() == 0) {
    throw TopologyError(surface.source() + ": the surface has no triangles");
  }
  if (!surface.has_normals()) surface.compute_normals();
  if (molecule != nullptr) {
    validate_molecule(*molecule);
    const Eigen::MatrixX3d points = surface.positions();
    surface.set_property(mesh::property::esp,
                         electrostatic_potential(points, *molecule, options.esp));
    surface.set_property(mesh::property::lp, lipophilic_potential(points, *molecule, options.lp));
  }
  const mesh::PrincipalCurvatures curvatures =
      mesh::principal_curvatures(surface, options.curvature);
  surface.set_property(mesh::property::cc1, curvatures.cc1);
  surface.set_property(mesh::property::cc2, curvatures.cc2);
  surface.set_property(mesh::property::shape_index, curvatures.shape_index);
  surface.set_property(mesh::property::curvedness, curvatures.curvedness);
}

}  // namespace surfcomp::molsurf
