#include "surfcomp/screening/screen.hpp"

namespace surfcomp::screening {

const options::Table<QueryScreenOptions>& screen_option_table() {
  using options::Kind;
  using Q = QueryScreenOptions;
  static const options::Table<Q> table = [] {
    options::Table<Q> t = {
        options::field<Q>(
            {"top", Kind::integer, "rows of the table (0: every molecule)", "", 0, 1e9},
            [](auto& q) -> auto& { return q.screen.top; }),
        options::field<Q>(
            {"refine", Kind::integer,
             "conformers of each molecule whose overlay is refined (stage 2), best "
             "fast score first (0: none)",
             "", 0, 1e6},
            [](auto& q) -> auto& { return q.screen.refine; }),
        options::field<Q>(
            {"refine-starts", Kind::integer,
             "principal-axes starts of each conformer refined in stage 2, best "
             "start score first (0: all)",
             "", 0, 24},
            [](auto& q) -> auto& { return q.screen.refine_starts; }),
        options::field<Q>(
            {"candidates", Kind::integer,
             "molecules given the full match (stage 3), best score after stage 2 "
             "first",
             "", 0, 1e6},
            [](auto& q) -> auto& { return q.screen.candidates; }),
        options::choice<Q>(
            {"fusion", Kind::choice,
             "with several queries, how a molecule's scores make the fused ranking: max "
             "(the best query's score) or mean"},
            [](auto& q) -> auto& { return q.screen.fusion; }, fusion_names),
        options::choice<Q>(
            {"chemistry", Kind::choice,
             "how a molecule query's hits are ranked, all found and posed with ESP, LP and "
             "heteroatoms beside shape: auto (by that score when the query carries an ionic "
             "group at pH 7, a formal charge that no bonded atom balances (as a nitro group's "
             "is) or an acid or base drawn neutral (a carboxylic acid, an aliphatic amine...); by "
             "the mean of that score and the shape Tanimoto of their pose otherwise; several "
             "queries all by the score when one has the group), on (by the score), or off (by "
             "shape)"},
            [](auto& q) -> auto& { return q.screen.chemistry; }, query_chemistry_names),
        options::field<Q>(
            molsurf::site_ligand_spec(), [](auto& q) -> auto& { return q.site_ligand; }),
        molsurf::sphere_option<Q>(
            molsurf::site_sphere_spec(), [](auto& q) -> auto& { return q.site_spheres; }),
        options::field<Q>(
            molsurf::site_pocket_spec(), [](auto& q) -> auto& { return q.site_pocket; }),
    };
    options::append(
        t, options::pick(molsurf::surface_input_option_table(), {"record"}),
        [](auto& q) -> auto& { return q.query.input; });
    options::append(
        t,
        options::pick(matching::match_option_table(),
                      {"atom-polish-sigma", "atom-polish-weight", "fine-top"}),
        [](auto& q) -> auto& { return q.screen.match; });
    options::append(
        t, molsurf::binding_site_option_table(), [](auto& q) -> auto& { return q.screen.site; });
    options::append(
        t, molsurf::pocket_option_table(), [](auto& q) -> auto& { return q.query.pockets; });
    t.push_back(options::threads_option<Q>([](auto& q) -> auto& { return q.query.threads; }));
    return t;
  }();
  return table;
}

bool is_site_query(const QueryScreenOptions& options) {
  return !options.site_ligand.empty() || !options.site_spheres.empty() || options.site_pocket > 0;
}

matching::MatchInput screen_query_input(matching::MatchInput query,
                                        const QueryScreenOptions& options) {
  query.site_ligand = options.site_ligand;
  query.site_pocket = options.site_pocket;
  query.site_spheres.insert(query.site_spheres.end(), options.site_spheres.begin(),
                            options.site_spheres.end());
  return query;
}

matching::MatchInputOptions screen_query_options(const QueryScreenOptions& options) {
  matching::MatchInputOptions query = options.query;
  query.site = options.screen.site;
  return query;
}

}  // namespace surfcomp::screening
