#include "surfcomp/matching/match.hpp"

namespace surfcomp::matching {

const options::Table<MatchOptions>& match_option_table() {
  using options::Kind;
  using M = MatchOptions;
  const std::vector<std::string> start_counts = {"0", "4", "24"};
  static const options::Table<M> table = {
      options::field<M>(
          {"shape-only", Kind::flag,
           "match by shape alone, ESP, LP and atoms set aside (the default "
           "for meshes that carry no ESP and LP)"},
          [](auto& m) -> auto& { return m.shape_only; }),
      options::field<M>(
          {"fuzzy-threshold", Kind::real, "fuzzy ESP/LP similarity threshold F", "", 0.0, 1.0},
          [](auto& m) -> auto& { return m.graph.fuzzy_threshold; }),
      options::field<M>(
          {"image-threshold", Kind::real, "harmonic shape image correlation threshold R", "", -1.0,
           1.0},
          [](auto& m) -> auto& { return m.graph.image_threshold; }),
      options::field<M>(
          {"distance-tolerance", Kind::real, "distance filter tolerance t", "A", 0.0, 100.0},
          [](auto& m) -> auto& { return m.graph.distance_tolerance; }),
      options::field<M>(
          {"min-distance", Kind::real, "distance filter minimum d_min", "A", 0.0, 100.0},
          [](auto& m) -> auto& { return m.graph.min_distance; }),
      options::field<M>(
          {"overlap-tolerance", Kind::real, "overlap filter tolerance j_tol", "degrees", 0.0,
           180.0},
          [](auto& m) -> auto& { return m.graph.overlap_tolerance_degrees; }),
      options::field<M>(
          {"max-graph-nodes", Kind::integer,
           "refuse a match whose association graph keeps more critical-point pairs "
           "than this after the image filter; its cost grows with the square of "
           "the count",
           "", 1, 1e15},
          [](auto& m) -> auto& { return m.graph.max_nodes; }),
      options::field<M>(
          {"max-clique-work", Kind::integer,
           "stop the clique search after this much work (a unit is one 64-node "
           "word of a set operation, a few ns) and go on with the cliques found, "
           "saying so",
           "", 1, 1e18},
          [](auto& m) -> auto& { return m.max_clique_work; }),
      options::field<M>(
          {"max-cliques", Kind::integer,
           "the clique budget: fit at most this many cliques, the first the search finds "
           "(each is fitted and merged, in time quadratic in their number); a match that "
           "reaches it says so in its notes",
           "", 1, 1e15},
          [](auto& m) -> auto& { return m.max_cliques; }),
      options::field<M>(
          {"rmsd-cut", Kind::real, "drop cliques whose fit RMSD exceeds this", "A", 0.0, 100.0,
           true},
          [](auto& m) -> auto& { return m.clustering.rmsd_cut; }),
      options::choice<M>(
          {"ranking", Kind::choice,
           "consensus: rank (rank-by-rank), number (rank-by-number) or vote "
           "(rank-by-vote)"},
          [](auto& m) -> auto& { return m.ranking.scheme; }, consensus_scheme_names),
      options::field<M>(
          {"refine-top", Kind::integer,
           "refine this many alignments on the whole surfaces and rank them by their "
           "overlay score (+ {atom_polish_weight} x atom fit between molecules; 0: the "
           "seed's consensus ranking alone)",
           "", 0, 1e6},
          [](auto& m) -> auto& { return m.refine_top; }),
      options::field<M>(
          {"fine-top", Kind::integer,
           "refine every start in single precision first, then only this many of the best "
           "again in double precision (0: every start in double precision)",
           "", 0, 1e6},
          [](auto& m) -> auto& { return m.fine_top; }),
      options::field<M>(
          {"overlay-sigma", Kind::real, "Gaussian width of the whole-surface overlay", "A", 0.1,
           10.0},
          [](auto& m) -> auto& { return m.overlay.sigma; }),
      options::field<M>(
          {"overlay-chem-weight", Kind::real,
           "weight of the ESP/LP Tanimoto against the shape Tanimoto in the overlay "
           "score",
           "", 0.0, 100.0},
          [](auto& m) -> auto& { return m.overlay.chem_weight; }),
      options::field<M>(
          {"overlay-atom-weight", Kind::real,
           "weight of the same-element heteroatom Tanimoto in the overlay score, "
           "where both inputs are molecules (or .hsi files built from molecules); "
           "not for site matches",
           "", 0.0, 1000.0},
          [](auto& m) -> auto& { return m.overlay.atom_weight; }),
      options::field<M>(
          {"polish-top", Kind::integer,
           "with the atom term, refine the first N alignments again on the whole "
           "score, heteroatoms pulled too, and order them again (0: no polish)",
           "", 0, 1e6},
          [](auto& m) -> auto& { return m.polish_top; }),
      options::field<M>(
          {"atom-polish-sigma", Kind::real,
           "where both inputs are molecules, polish the best alignments (match: the first "
           "{polish_top}) last on their heavy atoms, Gaussians of this width, like elements "
           "overlapping (0: no atom polish; else at least 0.05; not for site matches)",
           "A", 0.0, 5.0},
          [](auto& m) -> auto& { return m.atom_polish.sigma; }),
      options::field<M>(
          {"atom-polish-weight", Kind::real,
           "weight of the heavy-atom fit beside the overlay score in the atom polish and "
           "in the order of the scored alignments (between molecules)",
           "", 0.0, 100.0},
          [](auto& m) -> auto& { return m.atom_polish.weight; }),
      options::field<M>(
          {"overlay-tolerance", Kind::real,
           "a refinement stops when a step moves no sampled probe point farther "
           "than this",
           "A", 0.0, 10.0},
          [](auto& m) -> auto& { return m.overlay.tolerance; }),
      options::field<M>(
          {"coverage-distance", Kind::real,
           "a scored alignment's coverage is the larger of the fractions of each surface "
           "that lie within this distance of the other, the part's in a partial match "
           "(0: not computed)",
           "A", 0.0, 100.0},
          [](auto& m) -> auto& { return m.coverage_distance; }),
      options::field<M>(
          {"icp-top", Kind::integer,
           "polish the first N distinct alignments last by point-to-plane ICP on the whole "
           "surfaces (0: no ICP)",
           "", 0, 1e6},
          [](auto& m) -> auto& { return m.icp_top; }),
      options::field<M>(
          {"icp-max-distance", Kind::real, "the ICP polish pairs points no farther apart than this",
           "A", 0.01, 100.0},
          [](auto& m) -> auto& { return m.icp.max_distance; }),
      options::field<M>(
          {"principal-axes-starts", Kind::integer,
           "also refine this many principal-axes superpositions of the whole "
           "surfaces (with {refine_top} > 0; so do the site overlay options)",
           "", 0, 24, false, start_counts},
          [](auto& m) -> auto& { return m.principal_axes_starts; }),
      options::field<M>(
          {"site-overlay-radius", Kind::real,
           "site matches: overlay the vertices within this distance of the site's "
           "critical points",
           "A", 0.1, 100.0},
          [](auto& m) -> auto& { return m.site.overlay_radius; }),
      options::field<M>(
          {"site-chem-weight", Kind::real,
           "site matches: {overlay_chem_weight} for the pocket overlay", "", 0.0, 100.0},
          [](auto& m) -> auto& { return m.site.chem_weight; }),
      options::field<M>(
          {"site-lining-weight", Kind::real,
           "site matches: weight of the lining residues' composition in the site score "
           "(overlay + w lining) / (1 + w)",
           "", 0.0, 100.0},
          [](auto& m) -> auto& { return m.site.lining_weight; }),
      options::field<M>(
          {"site-principal-axes-starts", Kind::integer,
           "site matches: {principal_axes_starts} for the pocket overlay", "", 0, 24, false,
           start_counts},
          [](auto& m) -> auto& { return m.site.principal_axes_starts; }),
  };
  return table;
}

}  // namespace surfcomp::matching
